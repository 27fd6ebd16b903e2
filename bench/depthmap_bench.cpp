#include "bench/depthmap_bench.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <limits>
#include <random>
#include <string>

#include "bench/bench_pattern.hpp"
#include "bench/fft_pair.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/depthmap/depthmap.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/psf_exact.hpp"
#include "optimize/metrics/depth_loss.hpp"

namespace pinmask {
namespace {

Mask depthmap_bench_mask() {
    Mask m;
    m.camera.pixel_pitch_m = 3.45e-6;
    m.camera.sensor_cols = 512;
    m.camera.sensor_rows = 512;
    m.camera.lens_focal_m = 0.025;
    m.camera.sensor_distance_m = 0.020;
    m.camera.object_distance_m = 0.5;
    m.camera.wavelength_m = 530e-9;
    m.camera.pinhole_m = 115e-6;
    m.pattern = bench_pattern_16x16_k20();
    m.pattern.tiles_rows = m.pattern.tiles_cols = 2;
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "auto";
    return m;
}

}  // namespace

DepthmapBenchResult bench_depthmap(const DepthmapBenchOptions& o) {
    if (o.size < 64 || o.size > 4096) {
        throw invalid_field("size", std::to_string(o.size), "must be between 64 and 4096");
    }
    if (o.planes < 2 || o.planes > 100) {
        throw invalid_field("planes", std::to_string(o.planes), "must be between 2 and 100");
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    const Mask mask = depthmap_bench_mask();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    Plane scene(o.size, o.size);
    for (Eigen::Index i = 0; i < scene.size(); ++i) scene.data()[i] = uni(rng);
    ExactPsfOptions eo;
    eo.object_distance_m = 0.7;
    eo.rows = eo.cols = o.size;
    const Fft2 fft(o.size, o.size);
    const Plane capture =
        fft.inverse(fft.forward(scene) * psf2otf(exact_psf(mask, eo), o.size, o.size));
    DepthmapOptions d;
    d.distances_m = depth_range(0.4, 2.0, o.planes);
    d.window = std::min(121, o.size - (o.size % 2 == 0 ? 1 : 0));

    DepthmapBenchResult r;
    r.depthmap_seconds = std::numeric_limits<double>::infinity();
    r.depthmap_cpu_seconds = std::numeric_limits<double>::infinity();
    for (int k = 0; k < o.repeat; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        const DepthmapResult res = depthmap(capture, mask, d);
        r.depthmap_seconds =
            std::min(r.depthmap_seconds,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        r.depthmap_cpu_seconds =
            std::min(r.depthmap_cpu_seconds, double(std::clock() - c0) / CLOCKS_PER_SEC);
        r.capture_depth_m = res.capture_depth_m;
    }
    const FftPairTime f =
        measured_fft_pair(o.size, o.size, o.repeat, fft_threads_for(o.size, o.size));
    r.fft_pair_seconds = f.wall_seconds;
    r.fft_pair_cpu_seconds = f.cpu_seconds;
    return r;
}

}  // namespace pinmask
