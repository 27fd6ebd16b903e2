#include "bench/period_bench.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <random>
#include <string>

#include "bench/best_of.hpp"
#include "core/errors/error.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/capture/period.hpp"
#include "design/psf/psf.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"

namespace pinmask {
namespace {

Mask period_bench_mask() {
    Mask m;
    m.camera.pixel_pitch_m = 3.45e-6;
    m.camera.sensor_cols = 2448;
    m.camera.sensor_rows = 2048;
    m.camera.lens_focal_m = 0.025;
    m.camera.sensor_distance_m = 0.020;
    m.camera.object_distance_m = 2.0;
    m.camera.wavelength_m = 530e-9;
    m.camera.pinhole_m = 345e-6;
    m.pattern.n = 16;
    m.pattern.min_spacing_cells = 0.0;
    std::mt19937_64 rng(1);
    std::uniform_int_distribution<int> cell(0, 255);
    while (m.pattern.pinholes.size() < 20) {
        const int k = cell(rng);
        const Cell c{k / 16, k % 16};
        if (std::find(m.pattern.pinholes.begin(), m.pattern.pinholes.end(), c) ==
            m.pattern.pinholes.end()) {
            m.pattern.pinholes.push_back(c);
        }
    }
    m.psf.pixels_per_cell = 21;
    m.psf.kernel.model = "auto";
    return m;
}

}  // namespace

PeriodBenchResult bench_period(const PeriodBenchOptions& o) {
    for (const auto& [name, v] : {std::pair{"rows", o.rows}, std::pair{"cols", o.cols}}) {
        if (v < 672 || v > 8192) {
            throw invalid_field(name, std::to_string(v),
                                "must be between 672 (two 336 px periods) and 8192");
        }
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    const Mask m = period_bench_mask();
    const Plane psf = mask_psf(m);
    const int p = static_cast<int>(psf.rows());
    SimulationOptions so;
    so.noise.kind = NoiseKind::kGaussianSnr;
    so.noise.snr_db = 30.0;
    so.full_sensor = true;
    so.sensor_rows = o.rows;
    so.sensor_cols = o.cols;
    const Image scene = make_scene(scene_from_name("letter-R"), p, p);
    const Plane frame = simulate_capture(scene, psf, 20, 256, so).capture.channels[0];
    so.noise.snr_db = 10.0;
    const Plane doubted =
        simulate_capture(make_scene(scene_from_name("natural"), p, p), psf, 20, 256, so)
            .capture.channels[0];
    const TileOrigin origin = centred_tile_origin(o.rows, o.cols, p, p);
    const Plane period = frame.block(origin.row, origin.col, p, p);

    PeriodBenchResult r;
    r.rows = o.rows;
    r.cols = o.cols;
    r.period_px = p;
    PeriodCheck check;
    r.check_seconds = best_of(o.repeat, [&] { check = check_period(frame, p, p); });
    r.check_matches = check.matches();
    r.check_early_exit = check.rows.early_exit && check.cols.early_exit;
    r.doubted_check_seconds = best_of(o.repeat, [&] { check = check_period(doubted, p, p); });
    r.doubted_matches = check.matches();
    r.doubted_early_exit = check.rows.early_exit && check.cols.early_exit;
    DecodeOptions d;
    d.wiener.nsr = 1e-3;
    r.wiener_frame_seconds = best_of(o.repeat, [&] { decode_plane(frame, psf, d); });
    r.wiener_period_seconds = best_of(o.repeat, [&] { decode_plane(period, psf, d); });
    return r;
}

}  // namespace pinmask
