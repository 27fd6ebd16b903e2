// Comparison of masks and its report: compare() is `pinmask compare`, one call of the library
// transaction report/compare_run (baselines, metric rows, report pages), its result rendered by
// io/compare_json as the command's --json and written beside the report as its config.
#include <filesystem>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "io/compare_json.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/keyword_names.hpp"
#include "python/level_args.hpp"
#include "python/result.hpp"
#include "python/values.hpp"
#include "report/compare_run.hpp"

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
            CompareRequest q;
            q.noise = noise_levels_arg(snr_db, photons, sensor, CompareRequest::kDefaultSnrDb,
                                       &q.noise_text);
            q.prior = prior_arg(prior, prior_scenes);
            q.scenes = scenes;
            q.wiener_nsr = nsr;
            q.tv_lambda = tv_lambda;
            q.tv_iterations = tv_iterations;
            q.seed = seed;
            q.robust = robust;
            if (!depth && (depth_from || depth_to)) {
                throw InvalidInput(field_ref("depth_from_m") + "/" + field_ref("depth_to_m") +
                                   ": give depth=True (the range is the depth columns')");
            }
            q.depth = depth;
            q.depth_from_m = depth_from.value_or(0.0);
            q.depth_to_m = depth_to.value_or(0.0);
            q.baselines = baselines;
            q.baseline_count = baseline_count;
            q.report = report.value_or("");
            q.spell = [](const std::string& s) { return py_names::spell_keywords(s); };
            q.validate();
            int index = 0;
            for (const py::handle& h : masks) {
                ++index;
                const bool is_path = !py::isinstance<Mask>(h);
                const std::string path =
                    is_path ? py::str(h).cast<std::string>() : "mask " + std::to_string(index);
                Mask mk = mask_arg(h, allow_violations);
                if (!q.entries.empty()) require_same_camera(q.entries.front().mask, mk, path);
                q.entries.push_back({is_path ? fs::path(path).filename().string() : path, "input",
                                     is_path ? path : "python", std::move(mk)});
            }
            CompareReport r;
            {
                py::gil_scoped_release release;
                r = run_compare_request(std::move(q));
                io::write_compare_report(r);
            }
            return as_result(py::dict(json_value(io::compare_json(r))));
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
multi-page report (written atomically; SVG/PNG: one file per page). Returns what
`pinmask compare --json` prints: {masks (one row per mask, infinite figures as None),
psnr_columns (what each PSNR is computed on), settings, baselines (with baselines=True: random,
paper_like, mura; a baseline left out says why under 'skipped') and, with a report, report:
[paths written] and config: the NAME.config.json written beside it (this same dict)}.
Noise (snr_db or photons with the sensor stages), prior and robust (fabrication errors, as
--robust: 'size=44um,jitter=2um'; each row gains analytic_robust_wiener_psnr_db) as in metrics().
depth=True (needs photons): each row gains score(metrics='depth')'s keys over depth_from ..
depth_to metres (None, None: the working distance / 2 .. x 2).
The run is optimize/metrics/compare's run_compare (one camera rule, baselines, metric rows).)");
}

}  // namespace pinmask::python
