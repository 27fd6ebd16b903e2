// `pinmask compare`: masks side by side (metrics table on stdout or as JSON) and, with --report,
// a multi-page report (PDF, or SVG/PNG pages) with each mask's pictures. --baselines adds the
// median of random valid masks, the paper-like geometry and a MURA. The figures come from
// cli/compare_data (optimize/, decode/), the document from cli/compare_report, the drawing from
// export/report.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/analytic_setup.hpp"
#include "cli/command.hpp"
#include "cli/compare_data.hpp"
#include "cli/compare_report.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/output_set.hpp"
#include "core/units.hpp"
#include "export/report.hpp"

namespace pinmask::cli {
namespace {

using io::json_strict::finite_or_null;

namespace fs = std::filesystem;

struct Options {
    std::vector<std::string> masks;
    bool baselines = false;
    int baseline_count = 100;
    double snr_db = 30.0;
    std::string scenes = "letter-R,usaf";
    std::string filter = "optimal";
    std::string nsr = "tuned";
    std::string tv_lambda = "1e-3";
    int tv_iterations = 200;
    int prior_scenes = kDefaultPriorScenes;
    std::uint64_t seed = 1;
    bool allow_violations = false;
    std::string report;
    bool json = false;
};

CompareSettings make_settings(const Options& o) {
    CompareSettings s;
    s.snr_db = o.snr_db;
    std::istringstream in(o.scenes);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item.empty())
            throw invalid_field("--scenes", "'" + o.scenes + "'", "has an empty item");
        SceneSpec spec = scene_from_name(item);
        if (spec.kind == SceneKind::kNatural) spec.seed = 0;
        s.scenes.push_back(spec);
    }
    s.analytic_filter = parse_wiener_filter(o.filter);
    s.prior_scenes = o.prior_scenes;
    s.wiener_nsr = parse_weight_choice(o.nsr, "--nsr");
    s.tv_lambda = parse_weight_choice(o.tv_lambda, "--tv-lambda");
    s.tv_iterations = o.tv_iterations;
    s.seed = o.seed;
    validate(s);
    return s;
}

// Rule: a report describes one camera (page 1 prints it, the baselines are built for it), so
// every mask must be designed for the first mask's camera. Grid sizes may differ: each mask is
// simulated on its own period.
void require_same_camera(const Mask& first, const Mask& m, const std::string& path) {
    const Camera &a = first.camera, &b = m.camera;
    const std::pair<const char*, std::pair<double, double>> fields[] = {
        {"object_distance_m", {a.object_distance_m, b.object_distance_m}},
        {"lens_focal_m", {a.lens_focal_m, b.lens_focal_m}},
        {"sensor_distance_m", {a.sensor_distance_m, b.sensor_distance_m}},
        {"wavelength_m", {a.wavelength_m, b.wavelength_m}},
        {"pixel_pitch_m", {a.pixel_pitch_m, b.pixel_pitch_m}},
        {"pinhole_m", {a.pinhole_m, b.pinhole_m}},
        {"sensor_cols", {a.sensor_cols, b.sensor_cols}},
        {"sensor_rows", {a.sensor_rows, b.sensor_rows}}};
    for (const auto& [name, v] : fields) {
        if (v.first == v.second) continue;
        std::ostringstream s;
        s << v.second;
        std::ostringstream f;
        f << v.first;
        throw invalid_field(path + ": optics." + name, s.str(),
                            "differs from the first mask's " + f.str() +
                                "; a comparison report is for one camera (compare masks of "
                                "other cameras in separate runs)");
    }
}

nlohmann::ordered_json row_json(const CompareRow& r) {
    return {{"name", r.name},
            {"kind", r.kind},
            {"source", r.source},
            {"geometry_hash", r.geometry_hash},
            {"n", r.n},
            {"holes", r.holes},
            {"pixels_per_cell", r.pixels_per_cell},
            {"period_px", r.period_px},
            {"min_spacing_cells", r.min_spacing_cells},
            {"spacing_ok", r.spacing_ok},
            {"spacing_violations", r.spacing_violations},
            {"max_sidelobe", r.max_sidelobe},
            {"peak_to_sidelobe_ratio", finite_or_null(r.peak_to_sidelobe_ratio)},
            {"min_abs_pattern_spectrum", r.min_abs_pattern_spectrum},
            {"spectral_flatness", r.spectral_flatness},
            {"otf_condition_number", finite_or_null(r.otf_condition_number)},
            {"analytic_wiener_psnr_db", finite_or_null(r.analytic_wiener_psnr_db)},
            {"wiener_psnr_db", finite_or_null(r.wiener_psnr_db)},
            {"wiener_ssim", finite_or_null(r.wiener_ssim)},
            {"wiener_nsr", r.wiener_nsr},
            {"tv_psnr_db", finite_or_null(r.tv_psnr_db)},
            {"tv_ssim", finite_or_null(r.tv_ssim)},
            {"tv_lambda", r.tv_lambda}};
}

std::vector<std::string> settings_lines(const Options& o, const CompareSettings& s) {
    std::ostringstream a;
    a << "Simulation: SNR " << s.snr_db << " dB (Gaussian), scenes " << o.scenes
      << " (the first is shown on each page), Wiener NSR " << o.nsr << ", TV-L2 lambda "
      << o.tv_lambda << " (" << o.tv_iterations << " iterations max), noise seed " << o.seed
      << ". Analytic: " << o.filter << " Wiener filter, prior of " << o.prior_scenes
      << " natural textures.";
    return {a.str()};
}

void run(const Options& o) {
    const CompareSettings settings = make_settings(o);
    if (o.baseline_count < 1) {
        throw invalid_field("--baseline-count", std::to_string(o.baseline_count), "must be >= 1");
    }
    if (!o.report.empty()) {
        report_format(o.report, "--report");
        const fs::path dir = fs::path(o.report).parent_path();
        if (!dir.empty() && !fs::is_directory(dir)) {
            throw invalid_field("--report", o.report, "the output directory does not exist");
        }
    }
    {
        std::vector<NamedPath> inputs;
        for (const std::string& m : o.masks) inputs.push_back({"masks", m});
        fs::path config = o.report;  // the report's pages are checked again as they are staged
        if (!o.report.empty()) config.replace_filename(config.stem().string() + ".config.json");
        plan_outputs(inputs, {{"--report", o.report}, {"--report (config)", config}});
    }
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    std::vector<CompareEntry> entries;
    for (const std::string& path : o.masks) {
        CompareEntry e{fs::path(path).filename().string(), "input", path, io::read_mask_file(path, ro)};
        if (!entries.empty()) require_same_camera(entries.front().mask, e.mask, path);
        entries.push_back(std::move(e));
    }

    SceneCache scenes;
    CompareSummary summary;
    summary.camera = entries.front().mask.camera;
    summary.settings_lines = settings_lines(o, settings);
    nlohmann::ordered_json baselines_json = nlohmann::ordered_json::object();
    if (o.baselines) {
        const Mask tmpl = entries.front().mask;  // a copy: entries grows below
        std::cerr << "compare: random baseline, " << o.baseline_count << " draws\n";
        try {
            const RandomMedian rm =
                random_median_baseline(tmpl, o.baseline_count, settings, scenes);
            std::ostringstream l;
            l << std::fixed << std::setprecision(2)
              << "Baseline 'random median': " << rm.entry.source
              << ". Simulated Wiener PSNR of the " << rm.count << " draws: min " << rm.min_psnr_db
              << ", median " << rm.median_psnr_db << ", max " << rm.max_psnr_db << " dB.";
            summary.baseline_lines.push_back(l.str());
            baselines_json["random"] = {{"count", rm.count},
                                        {"first_seed", o.seed},
                                        {"median_seed", rm.median_seed},
                                        {"min_wiener_psnr_db", rm.min_psnr_db},
                                        {"median_wiener_psnr_db", rm.median_psnr_db},
                                        {"max_wiener_psnr_db", rm.max_psnr_db}};
            entries.push_back(rm.entry);
        } catch (const InvalidInput& e) {
            const std::string why = std::string("random baseline left out: ") + e.what();
            std::cerr << "compare: warning: " << why << "\n";
            summary.baseline_lines.push_back(why);
            baselines_json["random"] = {{"skipped", e.what()}};
        }
        entries.push_back(paper_like_baseline(tmpl, o.seed));
        summary.baseline_lines.push_back("Baseline 'paper-like': " + entries.back().source + ".");
        baselines_json["paper_like"] = {{"seed", o.seed}};
        const int p = mura_order_at_most(tmpl.pattern.n);
        if (p > 0) {
            entries.push_back(mura_baseline(tmpl, p));
            summary.baseline_lines.push_back("Baseline 'MURA': " + entries.back().source + ".");
            baselines_json["mura"] = {{"order", p}};
        } else {
            const std::string why = "MURA baseline left out: no prime p = 4m + 1 <= n = " +
                                    std::to_string(tmpl.pattern.n);
            std::cerr << "compare: warning: " << why << "\n";
            summary.baseline_lines.push_back(why + ".");
            baselines_json["mura"] = {{"skipped", why}};
        }
    }

    // A baseline can coincide with a given mask (e.g. generate's paper family with the same
    // seed); say so rather than leave two identical rows unexplained.
    for (std::size_t i = o.masks.size(); i < entries.size(); ++i) {
        for (std::size_t k = 0; k < o.masks.size(); ++k) {
            if (geometry_hash(entries[i].mask) == geometry_hash(entries[k].mask)) {
                entries[i].source += "; same geometry as " + entries[k].name;
                break;
            }
        }
    }
    std::vector<CompareResult> results;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        std::cerr << "compare: " << i + 1 << "/" << entries.size() << " " << entries[i].name
                  << "\n";
        results.push_back(compare_mask(entries[i], settings, scenes));
    }

    nlohmann::ordered_json j;
    for (const auto& r : results) j["masks"].push_back(row_json(r.row));
    j["settings"] = {{"snr_db", o.snr_db},
                     {"scenes", o.scenes},
                     {"analytic_filter", o.filter},
                     {"prior_scenes", o.prior_scenes},
                     {"wiener_nsr", o.nsr},
                     {"tv_lambda", o.tv_lambda},
                     {"tv_iterations", o.tv_iterations},
                     {"seed", o.seed},
                     {"baselines", o.baselines},
                     {"baseline_count", o.baseline_count}};
    if (o.baselines) j["baselines"] = baselines_json;
    std::vector<std::string> written;
    if (!o.report.empty()) {
        const ReportDocument doc = compare_document(results, settings, summary);
        StagedFiles files;
        for (const auto& [path, bytes] : render_report(doc, o.report)) {
            files.stage_bytes(path, bytes);
            written.push_back(path.string());
        }
        fs::path config = o.report;
        config.replace_filename(config.stem().string() + ".config.json");
        j["report"] = written;
        j["config"] = config.string();
        files.stage_bytes(config, j.dump(2) + "\n");
        files.commit();
    }
    if (o.json) {
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::cout << compare_table_text(compare_table(results));
    if (!written.empty()) {
        std::cout << "wrote " << written.size() << " report file(s): " << written.front()
                  << (written.size() > 1 ? " ..." : "") << " and " << j["config"].get<std::string>()
                  << "\n";
    }
}

constexpr const char* kFooter =
    "Table columns (also --json keys): K holes; n grid; spacing ok (spacing_ok: no pair closer "
    "than the mask's min spacing on the torus); max SL (max_sidelobe) and PSR "
    "(peak_to_sidelobe_ratio) of the torus autocorrelation; min|P^| (min_abs_pattern_spectrum) "
    "and flatness (spectral_flatness) of the pattern DFT; OTF cond (otf_condition_number) over "
    "the kernel passband; analytic W (analytic_wiener_psnr_db): closed-form expected Wiener PSNR "
    "as pinmask search computes it; sim W / sim TV (wiener_psnr_db, wiener_ssim, tv_psnr_db, "
    "tv_ssim): simulated one-period captures of --scenes at --snr decoded by Wiener and TV-L2, "
    "means over scenes. Infinite values are null in --json.\n"
    "--baselines adds: the median of --baseline-count random valid masks with the first mask's "
    "n, K, spacing, tiles, camera and PSF settings (draw i seeded with --seed + i, ranked by "
    "simulated Wiener PSNR, the lower median for an even count; pinmask generate --family random "
    "with that seed writes it again); the paper-like geometry (16 x 16, K 20, seeded with --seed); "
    "a MURA "
    "of the largest prime p = 4m + 1 <= n (breaks the spacing rule; it is half open).\n"
    "Rules: every mask must be for the first mask's camera (exit 2 otherwise); grid sizes may "
    "differ. --report r.pdf writes one PDF; r.svg or r.png write r-1.svg, r-2.svg ... (one per "
    "page); r.config.json (settings and table) is written beside them, all or nothing.\n"
    "Example: pinmask compare a.mask.json b.mask.json --baselines --snr 30 --scenes letter-R,usaf "
    "--report report.pdf";

void setup(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand(
        "compare",
        "Compare masks side by side: metrics table, optional baselines, and a multi-page report "
        "with each mask's pattern, PSF, log |OTF|, autocorrelation, a simulated capture and its "
        "Wiener and TV reconstructions.");
    cmd->footer(kFooter);
    cmd->add_option("masks", o->masks, "Mask files (*.mask.json); the first sets the camera")
        ->required();
    cmd->add_flag("--baselines", o->baselines,
                  "Add the random-median, paper-like and MURA baselines (see below)");
    cmd->add_option("--baseline-count", o->baseline_count,
                    "Random valid masks drawn for the random-median baseline (>= 1)")
        ->capture_default_str();
    cmd->add_option("--snr", o->snr_db, "Capture SNR in dB (Gaussian noise), all figures")
        ->capture_default_str();
    cmd->add_option("--scenes", o->scenes,
                    "Scenes for simulated figures, comma-separated: letter-R, usaf, siemens-star, "
                    "checker, point, natural, or image files; the first is shown in the report")
        ->capture_default_str();
    cmd->add_option("--filter", o->filter,
                    "Analytic Wiener filter: optimal (per-frequency) or nsr:VALUE, as pinmask "
                    "search")
        ->capture_default_str();
    cmd->add_option("--prior-scenes", o->prior_scenes,
                    "Natural textures averaged for the analytic prior (>= 1), as pinmask search")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr, "Simulated Wiener NSR (> 0), or 'tuned' per mask")
        ->capture_default_str();
    cmd->add_option("--tv-lambda", o->tv_lambda, "Simulated TV-L2 weight (> 0), or 'tuned' (slow)")
        ->capture_default_str();
    cmd->add_option("--tv-iters", o->tv_iterations, "TV-L2 maximum ADMM iterations (>= 1)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the noise and of the baselines' random draws")
        ->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Read masks that break their spacing rule even when the file does not record "
                  "that violations were allowed");
    cmd->add_option("--report", o->report,
                    "Report file: .pdf (one file) or .svg/.png (one file per page, name-1.svg "
                    "...), plus name.config.json");
    cmd->add_flag("--json", o->json,
                  "Print {masks: [...], settings, baselines, report} as JSON on stdout");
    cmd->callback([o] { run(*o); });
}

const Registration kCompare(65, "compare", setup);

}  // namespace
}  // namespace pinmask::cli
