#include "cli/outputs/error_time_json.hpp"

#include <cmath>
#include <thread>

#include "design/psf/kernel_model.hpp"
#include "io/mask_json.hpp"

namespace pinmask::cli {

using nlohmann::ordered_json;

namespace {

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

}  // namespace

ordered_json error_time_config_json(const Mask& mask, const std::string& source,
                                    const ErrorTimeSetup& setup,
                                    const std::vector<std::string>& scene_names,
                                    const ErrorTimeOptions& et, bool quick) {
    ordered_json iters = et.iterations, nsr = et.wiener_nsr, tik = et.tikhonov_lambda,
                 snrs = et.snr_db;
    return {{"format", "pinmask-bench-error-time-config"},
            {"version", 1},
            {"mask", source},
            {"geometry_hash", geometry_hash(mask)},
            {"period_px", setup.period_px},
            {"kernel", kernel_model_name(setup.kernel.model)},
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
            {"quick", quick},
            {"timing",
             "CPU time of decode_plane on one thread (CLOCK_THREAD_CPUTIME_ID), set-up included; "
             "median of the repeats; wall time in the CSV"},
            {"hardware_threads", std::thread::hardware_concurrency()},
            {"paper_reference_seconds",
             {{"wiener", kPaperWienerSeconds}, {"tvqc", kPaperTvqcSeconds}}}};
}

ordered_json error_time_summary_json(const ErrorTimeResult& r, const std::filesystem::path& out_dir,
                                     const std::vector<std::string>& plots) {
    ordered_json jb = ordered_json::array(), jp = ordered_json::array();
    for (const auto& d : r.summary) {
        ordered_json b = point_json(d.best);
        b["near_best"] = point_json(d.near_best);
        jb.push_back(b);
    }
    for (const auto& p : r.points) jp.push_back(point_json(p));
    ordered_json outputs = {{"csv", (out_dir / "error_time.csv").string()},
                            {"points_csv", (out_dir / "error_time_points.csv").string()},
                            {"markdown", (out_dir / "error_time.md").string()},
                            {"config", (out_dir / "error_time.config.json").string()},
                            {"plots", plots}};
    return ordered_json{{"outputs", outputs}, {"best", jb}, {"points", jp}};
}

}  // namespace pinmask::cli
