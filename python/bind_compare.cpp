// Comparison of masks and its report: compare() is `pinmask compare`'s library pipeline
// (optimize/metrics/compare run_compare: baselines, metric rows) and its report pages
// (report/compare_report, report/report); the CLI's report.config.json and its table text are not
// written here (the rows are returned instead).
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/atomic_file.hpp"
#include "io/mask_json.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "python/common.hpp"
#include "python/keyword_names.hpp"
#include "python/level_args.hpp"
#include "python/metrics_common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"
#include "report/compare_report.hpp"
#include "report/report.hpp"

namespace pinmask::python {

namespace {

namespace fs = std::filesystem;

}  // namespace

void bind_compare(py::module_& m) {
    m.def(
        "compare",
        [](const py::list& masks, const std::optional<std::string>& report, bool baselines,
           int baseline_count, const py::object& snr_db, const std::vector<std::string>& scenes,
           int prior_scenes, const std::string& nsr, const std::string& tv_lambda,
           int tv_iterations, std::uint64_t seed, bool allow_violations, const py::object& photons,
           std::optional<double> read_noise, std::optional<double> dark_current,
           std::optional<double> full_well, std::optional<int> bits,
           std::optional<double> optical_density, const py::object& prior,
           const std::optional<std::string>& robust, bool depth, std::optional<double> depth_from,
           std::optional<double> depth_to) {
            const SensorSettings sensor{read_noise, dark_current, full_well, optical_density, bits};
            std::string noise_text;
            CompareRunOptions options;
            options.settings = compare_settings(
                noise_levels_arg(snr_db, photons, sensor, {30.0}, &noise_text),
                prior_arg(prior, prior_scenes), scenes, nsr, tv_lambda, tv_iterations, seed);
            // robust: as `compare --robust` (score's parser: InvalidInput naming `robust`).
            if (robust) options.settings.metrics.robust = parse_fabrication_errors(*robust);
            if (!depth && (depth_from || depth_to)) {
                throw InvalidInput(field_ref("depth_from_m") + "/" + field_ref("depth_to_m") +
                                   ": give depth=True (the range is the depth columns')");
            }
            options.settings.metrics.depth = depth;
            options.settings.metrics.depth_range.from_m = depth_from.value_or(0.0);
            options.settings.metrics.depth_range.to_m = depth_to.value_or(0.0);
            options.baselines = baselines;
            options.baseline_count = baseline_count;
            options.validate();
            if (report) {
                report_format(*report, field_ref("report"));
                const fs::path dir = fs::path(*report).parent_path();
                if (!dir.empty() && !fs::is_directory(dir))
                    throw invalid_field(field_ref("report"), *report,
                                        "the output directory does not exist");
            }
            if (masks.empty()) throw InvalidInput("masks: give at least one mask");
            std::vector<CompareEntry> entries;
            int index = 0;
            for (const py::handle& h : masks) {
                ++index;
                const bool is_path = !py::isinstance<Mask>(h);
                const std::string path =
                    is_path ? py::str(h).cast<std::string>() : "mask " + std::to_string(index);
                Mask mk = mask_arg(h, allow_violations);
                if (!entries.empty()) require_same_camera(entries.front().mask, mk, path);
                entries.push_back({is_path ? fs::path(path).filename().string() : path, "input",
                                   is_path ? path : "python", std::move(mk)});
            }
            CompareOutcome outcome;
            std::vector<std::string> written;
            {
                py::gil_scoped_release release;
                outcome = run_compare(entries, options);
                // The library's words name settings by field: spelled as keywords (a given
                // mask's source is its path, left as typed).
                for (CompareResult& r : outcome.results)
                    if (r.row.kind != "input")
                        r.row.source = py_names::spell_keywords(r.row.source);
                for (std::string& l : outcome.baseline_lines) l = py_names::spell_keywords(l);
                outcome.random_skipped = py_names::spell_keywords(outcome.random_skipped);
                outcome.mura_skipped = py_names::spell_keywords(outcome.mura_skipped);
                if (report) {
                    CompareSummary summary;
                    summary.camera = entries.front().mask.camera;
                    summary.noise_text = noise_text;
                    summary.baseline_lines = outcome.baseline_lines;
                    std::string scene_list;
                    for (const auto& s : scenes) scene_list += (scene_list.empty() ? "" : ",") + s;
                    summary.settings_lines = {
                        "Simulation: " + summary.noise_text + ", scenes " + scene_list +
                        " (the first is shown on each page), Wiener NSR " + nsr +
                        ", TV-L2 lambda " + tv_lambda + " (" + std::to_string(tv_iterations) +
                        " iterations max), noise seed " + std::to_string(seed) +
                        ". Analytic prior: " + options.settings.metrics.prior.description() + "." +
                        (options.settings.metrics.robust.any()
                             ? " Robust W: analytic Wiener expected under fabrication errors (" +
                                   options.settings.metrics.robust.description() +
                                   "), decoded with the nominal PSF."
                             : "")};
                    const ReportDocument doc =
                        compare_document(outcome.results, options.settings, summary);
                    StagedFiles files;
                    for (const auto& [path, bytes] : render_report(doc, *report)) {
                        files.stage_bytes(path, bytes);
                        written.push_back(path.string());
                    }
                    files.commit();
                }
            }
            py::list rows;  // under "masks", the key of `pinmask compare --json`
            for (const auto& r : outcome.results) rows.append(row_dict(r.row));
            py::list warnings;
            for (const auto& w : {outcome.random_skipped, outcome.mura_skipped})
                if (!w.empty()) warnings.append(w);
            py::dict out;
            out["masks"] = rows;
            out["report"] = written;
            out["warnings"] = warnings;
            out["baselines"] = outcome.baseline_lines;
            return as_result(out);
        },
        py::arg("masks"), py::arg("report") = py::none(), py::arg("baselines") = false,
        py::arg("baseline_count") = 100, py::arg("snr_db") = py::none(),
        py::arg("scenes") = std::vector<std::string>{"letter-R", "usaf", "siemens-star"},
        py::arg("prior_scenes") = kDefaultPriorScenes, py::arg("nsr") = "tuned",
        py::arg("tv_lambda") = "1e-3", py::arg("tv_iterations") = 200, py::arg("seed") = 1,
        py::arg("allow_violations") = false, py::arg("photons") = py::none(),
        py::arg("read_noise") = py::none(), py::arg("dark_current") = py::none(),
        py::arg("full_well") = py::none(), py::arg("bits") = py::none(),
        py::arg("optical_density") = py::none(), py::arg("prior") = "natural",
        py::arg("robust") = py::none(), py::arg("depth") = false,
        py::arg("depth_from") = py::none(), py::arg("depth_to") = py::none(),
        R"(Compares masks (Mask objects or *.mask.json paths; one camera) as `pinmask compare`:
a metric row per mask (see metrics()), with baselines the median of baseline_count random
valid masks, the paper-like geometry and a MURA; report: a .pdf, .svg or .png path for the
multi-page report (written atomically; SVG/PNG: one file per page). Returns {masks (the rows of
`pinmask compare --json`'s masks), report:
[paths written], warnings: [baselines left out and why], baselines: [what each baseline is]}.
Noise (snr_db or photons with the sensor stages), prior and robust (fabrication errors, as
--robust: 'size=44um,jitter=2um'; each row gains robust_wiener_psnr_db) as in metrics().
depth=True (needs photons): each row gains score(metrics='depth')'s keys over depth_from ..
depth_to metres (None, None: the working distance / 2 .. x 2).
The run is optimize/metrics/compare's run_compare (one camera rule, baselines, metric rows).)");
}

}  // namespace pinmask::python
