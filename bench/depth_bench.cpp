#include "bench/depth_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <random>
#include <string>

#include "bench/bench_pattern.hpp"
#include "bench/fft_pair.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/pattern/mask.hpp"
#include "optimize/metrics/depth_loss.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

struct Times {
    double wall = 0, cpu = 0;
};

template <class F>
Times timed(F&& fn) {
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    fn();
    return {std::chrono::duration<double>(Clock::now() - t0).count(),
            double(std::clock() - c0) / CLOCKS_PER_SEC};
}

Mask depth_bench_mask() {
    Mask m;
    m.camera.pixel_pitch_m = 5.86e-6;
    m.camera.sensor_cols = 1920;
    m.camera.sensor_rows = 1200;
    m.camera.lens_focal_m = 0.075;
    m.camera.sensor_distance_m = 0.045;
    m.camera.object_distance_m = 1.2;
    m.camera.wavelength_m = 850e-9;
    m.camera.pinhole_m = 455.406e-6;
    m.pattern = bench_pattern_16x16_k20();
    m.psf.pixels_per_cell = 34;
    m.psf.kernel.model = "auto";
    return m;
}

}  // namespace

DepthBenchResult bench_depth(const DepthBenchOptions& o) {
    if (o.distances < 2 || o.distances > 100) {
        throw invalid_field("distances", std::to_string(o.distances), "must be between 2 and 100");
    }
    for (const auto& [name, v] : {std::pair{"rows", o.rows}, std::pair{"cols", o.cols}}) {
        if (v < 64 || v > 8192) {
            throw invalid_field(name, std::to_string(v), "must be between 64 and 8192");
        }
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    const Mask mask = depth_bench_mask();
    DepthOptions d;
    d.noise.kind = NoiseKind::kPhoton;
    d.noise.photons_per_pinhole = 20.0;
    d.noise.read_noise_e = 6.0;
    d.with_tv = o.with_tv;
    d.threads = o.threads;
    const std::vector<double> distances = depth_range(0.9, 2.0, o.distances);

    DepthBenchResult r;
    r.distances = o.distances;
    r.period_px = mask.pattern.n * mask.psf.pixels_per_cell;
    std::vector<DepthRecord> records;
    const Times t = timed([&] { records = depth_analysis(mask, distances, d); });
    r.depth_seconds = t.wall;
    r.depth_cpu_seconds = t.cpu;
    for (const DepthRecord& rec : records)
        r.worst_wiener_loss_db = std::max(r.worst_wiener_loss_db, rec.wiener_psnr_loss_db);

    const FftPairTime f =
        measured_fft_pair(o.rows, o.cols, o.repeat, fft_threads_for(o.rows, o.cols));
    r.fft_pair_seconds = f.wall_seconds;
    r.fft_pair_cpu_seconds = f.cpu_seconds;
    return r;
}

}  // namespace pinmask
