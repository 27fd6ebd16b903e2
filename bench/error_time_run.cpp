#include "bench/error_time_run.hpp"

#include <cstdio>
#include <random>

#include "bench/error_time_report.hpp"
#include "design/pattern/families.hpp"
#include "design/psf/psf.hpp"

namespace pinmask {

std::string error_time_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

Mask error_time_paper_mask() {
    Mask m;
    m.camera = paper_camera();
    std::mt19937_64 rng(1);
    m.pattern = paper_pattern(rng);
    m.psf.pixels_per_cell = 8;
    m.provenance.seed = 1;
    m.provenance.family = "paper";
    return m;
}

ErrorTimeSetup error_time_setup(const Mask& mask, const std::vector<SceneSpec>& scenes) {
    ErrorTimeSetup s;
    s.kernel = mask_kernel(mask);
    s.psf = synthesize_psf(mask.pattern, s.kernel, mask.psf.pixels_per_cell);
    s.period_px = static_cast<int>(s.psf.rows());
    const int m = s.period_px;
    for (const auto& spec : scenes) s.scenes.push_back({scene_name(spec), make_scene(spec, m, m)});
    return s;
}

ErrorTimeResult run_error_time_bench(const ErrorTimeSetup& setup, const ErrorTimeOptions& et,
                                     const std::string& mask_source) {
    ErrorTimeResult r;
    r.records = run_error_time(setup.psf, setup.scenes, et);
    r.points = mean_over_scenes(r.records);
    r.summary = summarise_decoders(r.points, kNearBestDb);
    r.markdown = error_time_markdown(r.summary);
    const int m = setup.period_px;
    std::string scene_list;
    for (const auto& s : setup.scenes) scene_list += (scene_list.empty() ? "" : ", ") + s.name;
    for (double snr : et.snr_db) {
        ErrorTimePlot plot;
        for (const auto& p : r.points)
            if (p.snr_db == snr) plot.points.push_back(p);
        plot.title = "PSNR against decode time, SNR " + error_time_number(snr) + " dB";
        plot.subtitle = "mask: " + mask_source + "; " + std::to_string(m) + " x " +
                        std::to_string(m) + " period; scenes: " + scene_list +
                        (et.repeats > 1 ? "; time: median of " + std::to_string(et.repeats) +
                                              " runs below 0.25 s"
                                        : "; time: one run per point");
        r.plots.push_back({"error_time_snr" + error_time_number(snr), std::move(plot)});
    }
    return r;
}

}  // namespace pinmask
