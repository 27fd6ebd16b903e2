#include "cli/decode_batch.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/options/decode_inputs.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/decode_files.hpp"
#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_folder.hpp"
#include "core/files/output_set.hpp"
#include "core/image/mosaic.hpp"
#include "core/limits/resource_limits.hpp"
#include "decode/capture/batch.hpp"
#include "decode/solvers/decode_method.hpp"
#include "io/capture_list.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

Bytes to_bytes(const std::string& s) { return Bytes(s.begin(), s.end()); }
std::string from_bytes(const Bytes& b) { return std::string(b.begin(), b.end()); }

// The deterministic record of one capture for the summary.
json capture_entry(const DecodeCommand& rc, const CaptureDecodeSummary& sum) {
    json channels = json::array();
    for (const DecodeResult& d : sum.channels) {
        channels.push_back({{"iterations", d.iterations},
                            {"residual", d.residual},
                            {"objective", d.objective},
                            {"converged", d.converged},
                            {"constraint_met", d.constraint_met}});
    }
    return {{"input", rc.capture},
            {"output", rc.output},
            {"window",
             {{"col", sum.window.col},
              {"row", sum.window.row},
              {"cols", sum.window.cols},
              {"rows", sum.window.rows}}},
            {"method", decode_method_name(sum.method)},
            {"single_precision", sum.single_precision},
            {"period", period_check_json(sum.period)},
            {"channels", channels}};
}

// Decodes one capture and stages its files exactly as `pinmask decode` writes them.
json decode_one(BatchDecoder& decoder, const DecodeCommand& rc, BayerMode bayer,
                StagedFiles& files) {
    const OutputKind kind = output_kind(rc.output);
    const std::optional<double> scale = parse_scale(rc.scale);
    json stats = {{"format", "pinmask-decode-stats"}, {"version", 2}};
    json timings;
    json shared_stats;
    RawInfo raw;
    Image capture = load_capture(rc.capture, bayer, stats, rc.bayer_given, &raw);
    for (const Plane& psf : decoder.shared().psf.channels)
        check_shared_psf_sampling(psf.rows(), psf.cols(), capture.rows(), capture.cols(), raw);
    const CaptureDecodeResult result = decoder.decode(std::move(capture));
    const CaptureDecodeSummary& sum = result.summary;
    std::istringstream warnings(period_warning(sum.period));
    for (std::string line; std::getline(warnings, line);)
        std::cerr << "pinmask: warning: " << rc.capture << ": " << line << "\n";
    if (!rc.quiet)  // a method or weight this capture makes poor (the stats keep them)
        for (const std::string& w : sum.warnings)
            std::cerr << "pinmask: warning: " << rc.capture << ": " << spell_flags(w) << "\n";
    add_summary_json(stats, timings, rc, sum);
    check_output_range(result.estimate, kind);
    const StagedDecode staged =
        stage_decode_files(files, rc, result.estimate, kind, scale, stats["chosen"]);
    if (!rc.stats.empty()) {
        stats["output"] = staged.output;
        stats["config"] = staged.config;
        stats["timings_s"] = timings;
        files.stage_bytes(rc.stats, stats.dump(2) + "\n");
    }
    return capture_entry(rc, sum);
}

}  // namespace

void run_decode_batch(const DecodeCommand& given, const BatchRequest& b, BayerMode bayer,
                      RankComm& comm) {
    DecodeCommand r = given;
    // Set-up: the same on every rank (same files, same flags), before any work.
    if (!r.capture.empty())
        throw invalid_field("--batch", b.list, "give either a capture or --batch, not both");
    if (!r.stats.empty())
        throw invalid_field("--stats", r.stats, "with --batch use --batch-stats (one per capture)");
    // -o is a folder, created when missing like every command's output folder, and removed
    // again when the run fails before writing into it.
    CreatedOutputFolder folder(r.output, "-o");
    const std::string ext = lower(b.format);
    if (ext != "tiff" && ext != "png" && ext != "npy")
        throw invalid_field("--batch-format", b.format, "must be tiff, png or npy");
    const std::vector<std::string> inputs = io::capture_list(b.list);
    std::vector<DecodeCommand> requests;
    std::map<std::string, std::string> by_stem;
    std::vector<NamedPath> in_paths = {
        {"--mask", r.mask}, {"--psf", r.psf}, {"--dark", r.dark}, {"--batch", b.list}};
    std::vector<NamedPath> out_paths;
    const fs::path dir = r.output;
    for (const std::string& path : inputs) {
        const std::string stem = fs::path(path).stem().string();
        const auto [it, fresh] = by_stem.emplace(stem, path);
        if (!fresh)
            throw invalid_field(
                "--batch", path,
                "has the same output name " + stem + "." + ext + " as " + it->second);
        DecodeCommand rc = r;
        rc.capture = path;
        rc.output = (dir / (stem + "." + ext)).string();
        rc.stats = b.stats ? (dir / (stem + ".stats.json")).string() : "";
        in_paths.push_back({"--batch", path});
        out_paths.push_back({"-o", rc.output, true});
        out_paths.push_back({"-o (config)", rc.output + ".config.json", true});
        if (b.stats) out_paths.push_back({"--batch-stats", rc.stats, true});
        requests.push_back(rc);
    }
    const std::string summary_path = (dir / "batch-summary.json").string();
    out_paths.push_back({"-o (summary)", summary_path, true});
    in_paths.push_back({"--nsr-map", r.nsr_map});
    plan_outputs(in_paths, out_paths);
    if (apply_refocus(r))
        for (DecodeCommand& rc : requests) rc.model = r.model, rc.crop = r.crop;
    resolve_request(r);
    for (DecodeCommand& rc : requests) rc.request = r.request;
    CaptureDecodeOptions options = capture_decode_options(r.request);
    options.decode.iterative.record_history = b.stats;  // only STEM.stats.json shows them
    options.validate();
    json shared_stats;
    load_nsr_map(r, options.decode, shared_stats);
    BatchDecoder decoder(load_shared_inputs(r, bayer,
                                            options.background == BackgroundMode::kCorner ||
                                                options.background == BackgroundMode::kAuto,
                                            shared_stats),
                         options);

    // This rank's captures; the first error stops this rank's work. A spent time budget
    // (PINMASK_TIME_LIMIT) stops it between captures: each rank decodes at least its first one,
    // and keeps every capture it finished.
    folder.create();
    StagedFiles files;  // after the folder: its temporaries go before the folder is removed
    const TimeLimitScope time_limited;
    json mine = {{"entries", json::array()}, {"time_limit", false}};
    bool first = true;
    for (std::size_t i : batch_share(requests.size(), comm.rank(), comm.size())) {
        if (!first && time_limit_spent()) {
            mine["time_limit"] = true;
            break;
        }
        first = false;
        try {
            json entry = decode_one(decoder, requests[i], bayer, files);
            mine["entries"].push_back({{"index", i}, {"entry", entry}});
        } catch (const std::exception& e) {
            mine["error"] = {{"index", i},
                             {"code", dynamic_cast<const InvalidInput*>(&e) ? 2 : 1},
                             {"message", e.what()}};
            break;
        }
    }
    // Rank 0 gathers, decides and stages the summary; every rank learns the verdict.
    const std::vector<Bytes> all = comm.gather(to_bytes(mine.dump()), 0);
    json verdict = {{"ok", true}, {"not_done", 0}};
    json summary;
    if (comm.rank() == 0) {
        std::vector<json> entries(requests.size());
        bool time_limit = false;
        for (const Bytes& bytes : all) {
            const json part = json::parse(from_bytes(bytes));
            for (const json& e : part["entries"])
                entries[e["index"].get<std::size_t>()] = e["entry"];
            time_limit = time_limit || part["time_limit"].get<bool>();
            if (part.contains("error") &&
                (verdict["ok"] || part["error"]["index"] < verdict["error"]["index"])) {
                verdict = {{"ok", false}, {"error", part["error"]}};
            }
        }
        // A capture no rank reached (the time budget was spent first) is listed with the reason
        // and no output.
        std::size_t not_done = 0;
        const std::string reason = time_limit ? time_limit_spent_text() : "";
        for (std::size_t i = 0; i < entries.size(); ++i) {
            if (!entries[i].is_null()) continue;
            ++not_done;
            entries[i] = {
                {"input", requests[i].capture}, {"output", nullptr}, {"not_done", reason}};
        }
        summary = {{"format", "pinmask-decode-batch"},
                   {"version", 1},
                   {"method", r.method},
                   {"psf", shared_stats["psf"]},
                   {"config", config_json(r)},
                   {"captures", entries}};
        summary["config"].erase("capture");
        summary["config"].erase("output");
        summary["config"].erase("stats");
        if (not_done > 0) {
            summary["stopped"] = {
                {"reason", reason}, {"done", requests.size() - not_done}, {"not_done", not_done}};
        }
        if (verdict["ok"]) {
            verdict["not_done"] = not_done;
            files.stage_bytes(summary_path, summary.dump(2) + "\n");
        }
    }
    Bytes verdict_bytes = to_bytes(verdict.dump());
    comm.broadcast(verdict_bytes, 0);
    verdict = json::parse(from_bytes(verdict_bytes));
    if (!verdict["ok"]) {
        const json& e = verdict["error"];
        const int code = e["code"].get<int>();
        if (comm.rank() != 0) throw BatchQuietExit{code};
        const std::string message = requests[e["index"].get<std::size_t>()].capture + ": " +
                                    e["message"].get<std::string>() + " (nothing written)";
        if (code == 2) throw InvalidInput(message);
        throw RuntimeFailure(message);
    }
    files.commit();
    folder.keep();
    comm.barrier();
    const auto not_done = verdict["not_done"].get<std::size_t>();
    if (comm.rank() == 0) {
        if (r.json) {
            std::cout << summary.dump(2) << "\n";
        } else {
            for (std::size_t i = 0; i < requests.size(); ++i) {
                if (summary["captures"][i]["output"].is_null()) continue;  // not done
                std::cout << "decode " << requests[i].capture << " -> " << requests[i].output
                          << "\n";
            }
            std::cout << "batch    " << requests.size() << " captures"
                      << (not_done > 0 ? " (" + std::to_string(not_done) + " not done)" : "")
                      << " on " << comm.size() << " rank(s), " << decoder.plans().filters_built()
                      << " filter(s) and " << decoder.plans().operators_built()
                      << " operator(s) built on rank 0\n"
                      << "  wrote    " << summary_path << "\n";
        }
    }
    if (not_done == 0) return;
    // The time budget left captures undone: exit code 3 on every rank.
    const std::string message =
        time_limit_spent_text() + ": decode --batch stopped after " +
        std::to_string(requests.size() - not_done) + " of " + std::to_string(requests.size()) +
        " captures; the others are listed in " + summary_path + " as not done";
    if (comm.size() == 1) throw TimeLimitSpent(message);
    // Under mpirun the first rank to exit non-zero ends the job: rank 0 says why first.
    if (comm.rank() == 0) std::cout.flush(), std::cerr << "pinmask: stopped: " << message << "\n";
    comm.barrier();
    throw BatchQuietExit{3};
}

}  // namespace pinmask::cli
