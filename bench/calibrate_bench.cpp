#include "bench/calibrate_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include "bench/best_of.hpp"
#include "bench/fft_pair.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/calibrate/calibrate.hpp"
#include "decode/calibrate/forward_fit.hpp"
#include "decode/calibrate/profile_table.hpp"
#include "design/optics/optics.hpp"
#include "design/pattern/random_sparse.hpp"

namespace pinmask {

namespace {

constexpr double kRotationDeg = 1.0, kPitchScale = 1.005, kFluxPerPinhole = 5e5;
constexpr double kBackground = 20.0, kReadNoise = 3.0;

Mask calibrate_bench_mask(int rows, int cols) {
    Mask m;
    m.camera.object_distance_m = 1.2;
    m.camera.lens_focal_m = 0.075;
    m.camera.sensor_distance_m = 0.045;
    m.camera.wavelength_m = 850e-9;
    m.camera.pixel_pitch_m = 5.86e-6;
    m.camera.pinhole_m = 455.4e-6;
    m.camera.sensor_cols = cols;
    m.camera.sensor_rows = rows;
    RandomSparseOptions ro;
    ro.n = 10;
    ro.holes = 15;
    ro.min_spacing_cells = 2.0;
    ro.tiles_rows = ro.tiles_cols = 6;
    std::mt19937_64 rng(3);
    m.pattern = random_sparse_pattern(ro, rng);
    m.psf.pixels_per_cell = 34;
    m.psf.kernel.model = "auto";
    return m;
}

}  // namespace

CalibrateBenchResult bench_calibrate(const CalibrateBenchOptions& o) {
    for (const auto& [name, v] : {std::pair{"rows", o.rows}, std::pair{"cols", o.cols}}) {
        if (v < 400 || v > 4096)
            throw invalid_field(name, std::to_string(v),
                                "must be between 400 (a 340 px period and its margin) and 4096");
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    const Mask m = calibrate_bench_mask(o.rows, o.cols);
    CalibrateBenchResult r;
    r.rows = o.rows;
    r.cols = o.cols;
    // The truth as a fit: the lattice centred on the sensor, every pinhole at the same flux.
    calibrate::ForwardFit truth;
    truth.family =
        calibrate::fit_family(m.camera, parse_kernel_model(m.psf.kernel.model, "kernel model"));
    const double pitch =
        magnification_at_u(m.camera) * m.camera.pinhole_m / m.camera.pixel_pitch_m * kPitchScale;
    const double t = kRotationDeg * std::numbers::pi / 180.0, ct = std::cos(t), st = std::sin(t);
    const double mc = 0.5 * (m.pattern.n * m.pattern.tiles_cols - 1);
    const double cx = 0.5 * (o.cols - 1), cy = 0.5 * (o.rows - 1);
    truth.lattice = {cx - pitch * (ct * mc + st * mc), cy - pitch * (-st * mc + ct * mc), t, pitch,
                     pitch};
    truth.median_gain = kFluxPerPinhole;
    int in_frame = 0;
    for (int tr = 0; tr < m.pattern.tiles_rows; ++tr)
        for (int tc = 0; tc < m.pattern.tiles_cols; ++tc)
            for (const Cell& c : m.pattern.pinholes) {
                calibrate::FittedPinhole p;
                p.mask_cell = {c.row + m.pattern.n * tr, c.col + m.pattern.n * tc};
                p.gain = kFluxPerPinhole;
                const double x =
                    truth.lattice.x0 + pitch * (ct * p.mask_cell.col + st * p.mask_cell.row);
                const double y =
                    truth.lattice.y0 + pitch * (-st * p.mask_cell.col + ct * p.mask_cell.row);
                in_frame += x >= 0 && y >= 0 && x <= o.cols - 1 && y <= o.rows - 1 ? 1 : 0;
                truth.pinholes.push_back(p);
            }
    const Plane psf = calibrate::fitted_psf(truth, m, o.rows, o.cols);
    std::mt19937_64 rng(1);
    std::normal_distribution<double> read(0.0, kReadNoise);
    Plane capture(o.rows, o.cols);
    for (Eigen::Index i = 0; i < capture.size(); ++i) {
        std::poisson_distribution<long> photons(psf.data()[i] * in_frame * kFluxPerPinhole +
                                                kBackground);
        capture.data()[i] = std::round(double(photons(rng)) + read(rng));
    }
    calibrate::CalibrationSummary s;
    r.calibrate_seconds =
        best_of(o.repeat, [&] { s = calibrate::calibrate_point_source(capture, std::nullopt, m); });
    r.pinholes_fitted = static_cast<int>(s.fit.pinholes.size());
    r.iterations = s.fit.iterations;
    r.rotation_deg = s.rotation_deg;
    r.rotation_sigma_deg = s.rotation_sigma_deg;
    r.true_rotation_deg = kRotationDeg;
    r.pitch_x_px = s.pitch_x_px;
    r.true_pitch_px = pitch;
    r.fft_pair_seconds = measured_fft_pair(o.rows, o.cols, std::max(3, o.repeat), 1).wall_seconds;
    return r;
}

}  // namespace pinmask
