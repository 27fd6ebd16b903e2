// `pinmask bench error-time`: PSNR against decode time of every decoder for one mask
// (bench/error_time.hpp), written as CSV, a plot per SNR (SVG + PNG) and a Markdown table, with
// the resolved configuration; all files are staged and appear together.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/error_time.hpp"
#include "bench/error_time_plot.hpp"
#include "bench/error_time_report.hpp"
#include "cli/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "design/families.hpp"
#include "design/kernel_model.hpp"
#include "design/psf.hpp"
#include "io/mask_json.hpp"
#include "optimize/scenes.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

struct Options {
    std::optional<std::string> mask;
    std::optional<std::string> preset;
    std::string scenes = "letter-R,usaf";
    std::string snr = "30";
    std::string iters = "1,3,10,30,100,300,1000";
    std::string nsr = "1e-4,3e-4,1e-3,3e-3,1e-2,3e-2,1e-1";
    std::string tikhonov_lambda = "1e-4,3e-4,1e-3,3e-3,1e-2";
    double tv_lambda = 1e-3;
    int repeats = 5;
    std::uint64_t seed = 1;
    bool quick = false;
    std::string output;
    bool json = false;
};

std::vector<std::string> split(const std::string& text, const std::string& flag) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (item.empty()) throw invalid_field(flag, "'" + text + "'", "has an empty list item");
        out.push_back(item);
    }
    if (out.empty()) throw invalid_field(flag, "''", "needs at least one item");
    return out;
}

std::vector<double> numbers(const std::string& text, const std::string& flag) {
    std::vector<double> out;
    for (const auto& s : split(text, flag)) out.push_back(parse_number(s, flag));
    return out;
}

std::vector<int> counts(const std::string& text, const std::string& flag) {
    std::vector<int> out;
    for (const auto& s : split(text, flag)) {
        const double v = parse_number(s, flag);
        if (v != std::floor(v) || v < 1 || v > 1e6) {
            throw invalid_field(flag, s, "must be an integer in 1..1000000");
        }
        out.push_back(static_cast<int>(v));
    }
    return out;
}

std::string g(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// The mask: a file, or the paper preset = `pinmask generate --family paper --seed 1`.
Mask load_mask(const Options& o, std::string& source) {
    if (o.mask && o.preset) {
        throw invalid_field("--preset", *o.preset, "give either a mask file or --preset, not both");
    }
    if (o.mask) {
        source = *o.mask;
        return io::read_mask_file(*o.mask);
    }
    Mask m;
    m.camera = paper_camera();
    std::mt19937_64 rng(1);
    m.pattern = paper_pattern(rng);
    m.psf.pixels_per_cell = 8;
    m.provenance.seed = 1;
    m.provenance.family = "paper";
    source = "preset paper (pinmask generate --family paper --seed 1)";
    return m;
}

ordered_json point_json(const ErrorTimePoint& p) {
    auto num = [](double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); };
    return {{"snr_db", p.snr_db},
            {"decoder", p.decoder},
            {"parameter", p.parameter},
            {"value", num(p.value)},
            {"iterations", p.iterations},
            {"seconds", p.seconds},
            {"wall_seconds", p.wall_seconds},
            {"psnr_db", num(p.psnr_db)},
            {"ssim", num(p.ssim)},
            {"scenes", p.scenes}};
}

void run(const Options& o) {
    // Flags first, before any work.
    ErrorTimeOptions et;
    et.snr_db = numbers(o.snr, "--snr");
    et.iterations = counts(o.iters, "--iters");
    et.wiener_nsr = numbers(o.nsr, "--nsr");
    et.tikhonov_lambda = numbers(o.tikhonov_lambda, "--tikhonov-lambda");
    et.tv_lambda = o.tv_lambda;
    et.repeats = o.repeats;
    et.seed = o.seed;
    if (o.quick) {
        et.iterations = {1, 10, 100};
        et.wiener_nsr = {1e-3, 1e-2};
        et.tikhonov_lambda = {1e-3};
        et.repeats = 1;
    }
    et.validate();
    const std::vector<std::string> scene_names = split(o.scenes, "--scenes");
    std::vector<SceneSpec> specs;
    for (const auto& s : scene_names) specs.push_back(scene_from_name(s));
    fs::path out_dir(o.output);
    if (!out_dir.has_filename()) out_dir = out_dir.parent_path();  // "out/" names "out"
    if (fs::exists(out_dir) && !fs::is_directory(out_dir)) {
        throw invalid_field("-o", o.output, "exists and is not a directory");
    }
    const fs::path parent = out_dir.parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) {
        throw invalid_field("-o", o.output, "its parent directory does not exist");
    }

    std::string source;
    const Mask mask = load_mask(o, source);
    const Kernel kernel = mask_kernel(mask);
    const Plane psf = synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell);
    const int m = static_cast<int>(psf.rows());
    std::vector<NamedScene> scenes;
    for (const auto& s : specs) scenes.push_back({scene_name(s), make_scene(s, m, m)});

    std::string last;
    et.progress = [&](const std::string& msg) {
        // One stderr line per (SNR, scene, decoder): the text up to the decoder's setting.
        // msg = "snr S dB, SCENE, DECODER[ PARAM VALUE][, K iterations]"
        const std::size_t a = msg.find(", "), b = msg.find(", ", a + 2);
        const std::size_t c = msg.find_first_of(" ,", b + 2);
        const std::string head = msg.substr(0, c);
        if (head != last) std::cerr << "error-time: " << head << "\n";
        last = head;
    };
    std::cerr << "error-time: mask " << source << ", " << m << " x " << m << " period, kernel "
              << kernel_model_name(kernel.model) << "; timing on one thread\n";
    const std::vector<ErrorTimeRecord> records = run_error_time(psf, scenes, et);
    const std::vector<ErrorTimePoint> points = mean_over_scenes(records);
    const std::vector<DecoderSummary> summary = summarise_decoders(points, kNearBestDb);
    const std::string markdown = error_time_markdown(summary);

    fs::create_directories(out_dir);
    StagedFiles files;
    files.stage_bytes(out_dir / "error_time.csv", error_time_csv(records));
    files.stage_bytes(out_dir / "error_time_points.csv", error_time_points_csv(points));
    files.stage_bytes(out_dir / "error_time.md", markdown);
    std::string scene_list;
    for (const auto& s : scenes) scene_list += (scene_list.empty() ? "" : ", ") + s.name;
    ordered_json plots = ordered_json::array();
    for (double snr : et.snr_db) {
        ErrorTimePlot plot;
        for (const auto& p : points)
            if (p.snr_db == snr) plot.points.push_back(p);
        plot.title = "PSNR against decode time, SNR " + g(snr) + " dB";
        plot.subtitle = "mask: " + source + "; " + std::to_string(m) + " x " + std::to_string(m) +
                        " period; scenes: " + scene_list +
                        (et.repeats > 1 ? "; time: median of " + std::to_string(et.repeats) +
                                              " runs below 0.25 s"
                                        : "; time: one run per point");
        const std::string stem = "error_time_snr" + g(snr);
        files.stage(out_dir / (stem + ".svg"),
                    [&](const fs::path& tmp) { write_error_time_svg(tmp, plot); });
        files.stage(out_dir / (stem + ".png"),
                    [&](const fs::path& tmp) { write_error_time_png(tmp, plot); });
        plots.push_back((out_dir / (stem + ".svg")).string());
        plots.push_back((out_dir / (stem + ".png")).string());
    }
    ordered_json iters = et.iterations, nsr = et.wiener_nsr, tik = et.tikhonov_lambda,
                 snrs = et.snr_db;
    const ordered_json config = {
        {"format", "pinmask-bench-error-time-config"},
        {"version", 1},
        {"mask", source},
        {"geometry_hash", geometry_hash(mask)},
        {"period_px", m},
        {"kernel", kernel_model_name(kernel.model)},
        {"scenes", scene_names},
        {"snr_db", snrs},
        {"iterations", iters},
        {"wiener_nsr", nsr},
        {"tikhonov_lambda", tik},
        {"tikhonov_regulariser", "gradient"},
        {"tv_lambda", et.tv_lambda},
        {"tvqc_eps", "from the true noise sigma: sigma sqrt(N) sqrt(1 + 2 sqrt(2 / N))"},
        {"repeats", et.repeats},
        {"repeat_below_seconds", et.repeat_below_seconds},
        {"seed", et.seed},
        {"quick", o.quick},
        {"timing",
         "CPU time of decode_plane on one thread (CLOCK_THREAD_CPUTIME_ID), set-up included; "
         "median of the repeats; wall time in the CSV"},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"paper_reference_seconds",
         {{"wiener", kPaperWienerSeconds}, {"tvqc", kPaperTvqcSeconds}}}};
    files.stage_bytes(out_dir / "error_time.config.json", config.dump(2) + "\n");
    files.commit();

    if (o.json) {
        ordered_json jb = ordered_json::array(), jp = ordered_json::array();
        for (const auto& d : summary) {
            ordered_json b = point_json(d.best);
            b["near_best"] = point_json(d.near_best);
            jb.push_back(b);
        }
        for (const auto& p : points) jp.push_back(point_json(p));
        ordered_json outputs = {{"csv", (out_dir / "error_time.csv").string()},
                                {"points_csv", (out_dir / "error_time_points.csv").string()},
                                {"markdown", (out_dir / "error_time.md").string()},
                                {"config", (out_dir / "error_time.config.json").string()},
                                {"plots", plots}};
        std::cout << ordered_json{{"outputs", outputs}, {"best", jb}, {"points", jp}}.dump()
                  << "\n";
        return;
    }
    std::cout << markdown << "\nwrote " << files.final_paths().size() << " files to "
              << out_dir.string() << "\n";
}

}  // namespace

void add_bench_error_time(CLI::App& bench) {
    auto o = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "error-time",
        "PSNR against decode time of every decoder for one mask: Wiener at several NSR, "
        "gradient Tikhonov at several lambda, TV-L2, TVQC and Richardson-Lucy after 1..1000 "
        "iterations, on simulated one-period captures with Gaussian noise at each SNR. "
        "Writes CSV, a plot per SNR (SVG + PNG) and a Markdown table of the best point per "
        "decoder.");
    auto* mask = cmd->add_option("mask", o->mask, "Mask file (*.mask.json)");
    cmd->add_option("--preset", o->preset,
                    "Use a built-in mask instead of a file: paper = `pinmask generate "
                    "--family paper --seed 1` (the default when no mask is given)")
        ->check(CLI::IsMember({"paper"}))
        ->excludes(mask);
    cmd->add_option("--scenes", o->scenes,
                    "Comma-separated scenes (letter-R, usaf, siemens-star, checker, point, "
                    "natural, or image files), rendered at one period")
        ->capture_default_str();
    cmd->add_option("--snr", o->snr, "Comma-separated SNRs in dB (Gaussian noise)")
        ->capture_default_str();
    cmd->add_option("--iters", o->iters,
                    "Comma-separated iteration counts of the iterative decoders; each count "
                    "is a separate run (solver state is not resumable)")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr, "Comma-separated Wiener noise-to-signal ratios")
        ->capture_default_str();
    cmd->add_option("--tikhonov-lambda", o->tikhonov_lambda,
                    "Comma-separated gradient-Tikhonov weights")
        ->capture_default_str();
    cmd->add_option("--tv-lambda", o->tv_lambda, "TV-L2 weight (> 0)")->capture_default_str();
    cmd->add_option("--repeats", o->repeats,
                    "Timed runs of a point faster than 0.25 s; the median is kept (>= 1)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the noise")->capture_default_str();
    cmd->add_flag("--quick", o->quick,
                  "Small sweep for smoke tests: iterations 1,10,100, NSR 1e-3,1e-2, Tikhonov "
                  "1e-3, one timed run per point (overrides those flags)");
    cmd->add_option("-o,--output", o->output, "Output directory (created; its parent must exist)")
        ->required();
    cmd->add_flag("--json", o->json,
                  "Print the output paths, the best point per decoder and every curve point "
                  "as one JSON object on stdout");
    cmd->footer(
        "Files in the output directory: error_time.csv (every scene and setting), "
        "error_time_points.csv (means over scenes: the plotted points), error_time.md (best "
        "point per decoder), error_time_snrS.svg/.png (time on a log axis, PSNR on y, the "
        "paper's Wiener 0.004 s and TVQC 7.2 s marked as times), error_time.config.json.\n"
        "Time: CPU seconds of one decode on one thread (decoders and FFTW are single-threaded, "
        "so this is the wall time of an idle machine; wall time is in the CSV), filter or "
        "operator set-up included, FFTW plans made before timing. TVQC's eps comes from the "
        "true noise sigma (l1-magic rule); Tikhonov uses the gradient regulariser. The "
        "paper's timings come from its own machine and code.\n"
        "Example: pinmask bench error-time --preset paper --scenes letter-R,usaf --snr 30 "
        "-o bench-out/");
    cmd->callback([o] { run(*o); });
}

}  // namespace pinmask::cli
