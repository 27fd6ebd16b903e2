// Comparison of masks and its report (cli/compare_data, cli/compare_report, export/report):
// compare() follows `pinmask compare` (cli/cmd_compare.cpp): the same settings, baselines,
// metric rows and report files; the CLI's report.config.json and its table text are not
// written here (the rows are returned instead).
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "cli/compare_report.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "export/report.hpp"
#include "io/mask_json.hpp"
#include "python/common.hpp"
#include "python/metrics_common.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

namespace fs = std::filesystem;

// `pinmask compare`'s rule: a report is for one camera.
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
        std::ostringstream s, f;
        s << v.second;
        f << v.first;
        throw invalid_field(path + ": optics." + name, s.str(),
                            "differs from the first mask's " + f.str() +
                                "; a comparison report is for one camera (compare masks of "
                                "other cameras in separate runs)");
    }
}

}  // namespace

void bind_compare(py::module_& m) {
    m.def(
        "compare",
        [](const py::list& masks, const std::optional<std::string>& report, bool baselines,
           int baseline_count, double snr_db, const std::vector<std::string>& scenes,
           const std::string& filter, int prior_scenes, const std::string& nsr,
           const std::string& tv_lambda, int tv_iterations, std::uint64_t seed,
           bool allow_violations) {
            const cli::CompareSettings settings = compare_settings(
                snr_db, scenes, filter, prior_scenes, nsr, tv_lambda, tv_iterations, seed);
            if (baseline_count < 1)
                throw invalid_field("--baseline-count", std::to_string(baseline_count),
                                    "must be >= 1");
            if (report) {
                report_format(*report, "--report");
                const fs::path dir = fs::path(*report).parent_path();
                if (!dir.empty() && !fs::is_directory(dir))
                    throw invalid_field("--report", *report, "the output directory does not exist");
            }
            if (masks.empty()) throw InvalidInput("masks: give at least one mask");
            std::vector<cli::CompareEntry> entries;
            int index = 0;
            for (const py::handle& h : masks) {
                ++index;
                const bool is_path = !py::isinstance<Mask>(h);
                const std::string path =
                    is_path ? py::str(h).cast<std::string>() : "mask " + std::to_string(index);
                cli::CompareEntry e{is_path ? fs::path(path).filename().string() : path, "input",
                                    is_path ? path : "python", mask_arg(h, allow_violations)};
                if (!entries.empty()) require_same_camera(entries.front().mask, e.mask, path);
                entries.push_back(std::move(e));
            }
            const std::size_t given = entries.size();
            std::vector<cli::CompareResult> results;
            std::vector<std::string> written;
            py::list warnings;
            {
                py::gil_scoped_release release;
                cli::SceneCache cache;
                cli::CompareSummary summary;
                summary.camera = entries.front().mask.camera;
                std::ostringstream a;
                std::string scene_list;
                for (const auto& s : scenes) scene_list += (scene_list.empty() ? "" : ",") + s;
                a << "Simulation: SNR " << snr_db << " dB (Gaussian), scenes " << scene_list
                  << " (the first is shown on each page), Wiener NSR " << nsr << ", TV-L2 lambda "
                  << tv_lambda << " (" << tv_iterations << " iterations max), noise seed " << seed
                  << ". Analytic: " << filter << " Wiener filter, prior of " << prior_scenes
                  << " natural textures.";
                summary.settings_lines = {a.str()};
                if (baselines) {
                    const Mask tmpl = entries.front().mask;
                    try {
                        const cli::RandomMedian rm =
                            cli::random_median_baseline(tmpl, baseline_count, settings, cache);
                        std::ostringstream l;
                        l << std::fixed << std::setprecision(2)
                          << "Baseline 'random median': " << rm.entry.source
                          << ". Simulated Wiener PSNR of the " << rm.count << " draws: min "
                          << rm.min_psnr_db << ", median " << rm.median_psnr_db << ", max "
                          << rm.max_psnr_db << " dB.";
                        summary.baseline_lines.push_back(l.str());
                        entries.push_back(rm.entry);
                    } catch (const InvalidInput& e) {
                        const std::string why =
                            std::string("random baseline left out: ") + e.what();
                        summary.baseline_lines.push_back(why);
                        py::gil_scoped_acquire gil;
                        warnings.append(why);
                    }
                    entries.push_back(cli::paper_like_baseline(tmpl, seed));
                    summary.baseline_lines.push_back(
                        "Baseline 'paper-like': " + entries.back().source + ".");
                    const int p = cli::mura_order_at_most(tmpl.pattern.n);
                    if (p > 0) {
                        entries.push_back(cli::mura_baseline(tmpl, p));
                        summary.baseline_lines.push_back(
                            "Baseline 'MURA': " + entries.back().source + ".");
                    } else {
                        const std::string why =
                            "MURA baseline left out: no prime p = 4m + 1 <= n = " +
                            std::to_string(tmpl.pattern.n);
                        summary.baseline_lines.push_back(why + ".");
                        py::gil_scoped_acquire gil;
                        warnings.append(why);
                    }
                }
                for (std::size_t i = given; i < entries.size(); ++i) {
                    for (std::size_t k = 0; k < given; ++k) {
                        if (geometry_hash(entries[i].mask) == geometry_hash(entries[k].mask)) {
                            entries[i].source += "; same geometry as " + entries[k].name;
                            break;
                        }
                    }
                }
                for (const auto& e : entries)
                    results.push_back(cli::compare_mask(e, settings, cache));
                if (report) {
                    const ReportDocument doc = cli::compare_document(results, settings, summary);
                    StagedFiles files;
                    for (const auto& [path, bytes] : render_report(doc, *report)) {
                        files.stage_bytes(path, bytes);
                        written.push_back(path.string());
                    }
                    files.commit();
                }
            }
            py::list rows;
            for (const auto& r : results) rows.append(row_dict(r.row));
            py::dict out;
            out["rows"] = rows;
            out["report"] = written;
            out["warnings"] = warnings;
            return out;
        },
        py::arg("masks"), py::arg("report") = py::none(), py::arg("baselines") = false,
        py::arg("baseline_count") = 100, py::arg("snr_db") = 30.0,
        py::arg("scenes") = std::vector<std::string>{"letter-R", "usaf"},
        py::arg("filter") = "optimal", py::arg("prior_scenes") = cli::kDefaultPriorScenes,
        py::arg("nsr") = "tuned", py::arg("tv_lambda") = "1e-3", py::arg("tv_iterations") = 200,
        py::arg("seed") = 1, py::arg("allow_violations") = false,
        R"(Compares masks (Mask objects or *.mask.json paths; one camera) as `pinmask compare`:
a metric row per mask (see metrics()), with baselines the median of baseline_count random
valid masks, the paper-like geometry and a MURA; report: a .pdf, .svg or .png path for the
multi-page report (written atomically; SVG/PNG: one file per page). Returns {rows, report:
[paths written], warnings: [baselines left out and why]}.)");
}

}  // namespace pinmask::python
