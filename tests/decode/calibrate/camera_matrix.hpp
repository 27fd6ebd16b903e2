// The camera matrix of the calibration tests: cameras the project does not design for, a
// perturbed fabricated mask per case, point-source captures and scenes rendered by the independent
// forward model of point_source_model.hpp (its own diffraction integral, rotation, noise), and the
// decodes that compare the calibrated, design and true PSFs. Shared by test_camera_matrix.cpp and
// test_calibrate_coverage.cpp.
#pragma once

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/fft/fft.hpp"
#include "decode/calibrate/calibrate.hpp"
#include "decode/capture/decoder.hpp"
#include "design/optics/camera.hpp"
#include "design/optics/optics.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "tests/decode/calibrate/point_source_model.hpp"

namespace pinmask::test {

struct CameraCase {
    std::string name;
    Camera camera;
    int n = 10, holes = 15, ppc = 8;
    int rows = 200, cols = 200;
};

// A monochrome camera by name of field (a brace list would shift when Camera gains a field: the
// band's width once took the pixel pitch's place); the pinhole side is set by the case.
inline Camera optics(double u_m, double lens_focal_m, double sensor_distance_m, double wavelength_m,
                     double pixel_pitch_m, int cols, int rows) {
    Camera k;
    k.object_distance_m = u_m;
    k.lens_focal_m = lens_focal_m;
    k.sensor_distance_m = sensor_distance_m;
    k.wavelength_m = wavelength_m;
    k.bandwidth_m = 0.0;
    k.pixel_pitch_m = pixel_pitch_m;
    k.pinhole_m = 0.0;
    k.sensor_cols = cols;
    k.sensor_rows = rows;
    return k;
}

// Cameras: the paper's (8 px per cell), a C-mount (20), a phone-like 1.12 um sensor (16), the
// issue's NIR camera (34 px per cell, spots one cell wide: N = 0.59 with the lens), a lensless
// one (33) and the walkthrough's (the NIR optics with a 120 um pinhole: 9 px per cell, spots six
// cells wide). Each pinhole side is solved for whole pixels per cell at u (as design does).
inline CameraCase camera_case(const std::string& name) {
    CameraCase c;
    c.name = name;
    Camera& k = c.camera;
    if (name == "paper") {
        k = paper_camera();
        c.n = 16;
        c.holes = 20;
        c.ppc = 8;
        c.rows = c.cols = 200;
    } else if (name == "c-mount") {
        k = optics(2.0, 0.025, 0.015, 550e-9, 5.5e-6, 1280, 1024);
        c.n = 8;
        c.holes = 10;
        c.ppc = 20;
        c.rows = c.cols = 240;
    } else if (name == "phone") {
        k = optics(0.5, 0.004, 0.0035, 550e-9, 1.12e-6, 4000, 3000);
        c.n = 10;
        c.holes = 14;
        c.ppc = 16;
        c.rows = c.cols = 240;
    } else if (name == "nir") {
        k = optics(1.2, 0.075, 0.045, 850e-9, 5.86e-6, 1920, 1200);
        c.n = 10;
        c.holes = 15;
        c.ppc = 34;
        c.rows = c.cols = 340;
    } else if (name == "walkthrough") {
        // examples/python/walkthrough.py's camera: the NIR optics on a 640 x 480 sensor with a
        // 120 um pinhole, 9 px per cell at u (8.96), N = 0.04: each spot's main lobe is +-54 px,
        // six cells, wider than the 2.5-cell window the fit used to hold each spot in.
        k = optics(1.2, 0.075, 0.045, 850e-9, 5.86e-6, 640, 480);
        k.pinhole_m = 120e-6;
        c.n = 8;
        c.holes = 6;
        c.ppc = 9;
        c.rows = 200;
        c.cols = 240;
    } else if (name == "lensless") {
        k = optics(2.0, INFINITY, 0.020, 550e-9, 5e-6, 1280, 1024);
        c.n = 10;
        c.holes = 15;
        c.ppc = 33;
        c.rows = c.cols = 340;
    }
    if (k.pinhole_m == 0.0) k.pinhole_m = c.ppc * k.pixel_pitch_m / magnification_at_u(k);
    return c;
}

// A pattern of `holes` cells on the n x n torus, no two in each other's 8-neighbourhood, seeded.
inline Pattern spaced_pattern(int n, int holes, unsigned seed) {
    std::mt19937_64 rng(seed);
    for (int attempt = 0; attempt < 1000; ++attempt) {
        std::vector<Cell> cells;
        std::vector<Cell> all;
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) all.push_back({r, c});
        std::shuffle(all.begin(), all.end(), rng);
        for (const Cell& a : all) {
            bool ok = true;
            for (const Cell& b : cells) {
                const int dr = std::min(std::abs(a.row - b.row), n - std::abs(a.row - b.row));
                const int dc = std::min(std::abs(a.col - b.col), n - std::abs(a.col - b.col));
                ok = ok && std::max(dr, dc) >= 2;
            }
            if (ok) cells.push_back(a);
            if (static_cast<int>(cells.size()) == holes) break;
        }
        if (static_cast<int>(cells.size()) == holes) {
            std::sort(cells.begin(), cells.end());
            Pattern p;
            p.n = n;
            p.pinholes = cells;
            p.tiles_rows = p.tiles_cols = 2;
            return p;
        }
    }
    return {};
}

inline Mask case_mask(const CameraCase& c, unsigned seed) {
    Mask m;
    m.camera = c.camera;
    m.pattern = spaced_pattern(c.n, c.holes, seed);
    m.psf.pixels_per_cell = c.ppc;
    m.psf.kernel.model = "auto";
    return m;
}

struct Perturbation {
    double rotation_deg = 0.0;
    double pitch_x = 1.0, pitch_y = 1.0;  // scale of the pitch at u
    double side = 1.0;                    // scale of the pinhole side
    int missing = 0;
    double optical_density = INFINITY;  // leak T = 10^-OD of an open cell's light per cell
    double flux = 0.0;                  // counts per pinhole (0: 800 counts per pixel of a cell)
    unsigned seed = 1;
};

// The perturbed capture's scene parameters: pitch and side at u from the camera, the lattice
// placed so the frame's centre sees the mask's centre plus a sub-pixel offset.
inline PointSourceScene scene_of(const CameraCase& c, const Mask& m, const Perturbation& p) {
    PointSourceScene s;
    s.pattern = m.pattern;
    s.rows = c.rows;
    s.cols = c.cols;
    const Camera& k = c.camera;
    const double pitch = magnification_at_u(k) * k.pinhole_m / k.pixel_pitch_m;
    s.pitch_x = pitch * p.pitch_x;
    s.pitch_y = pitch * p.pitch_y;
    s.rotation_deg = p.rotation_deg;
    // Diffraction: a = d w / (lambda f), N = d^2 |1/z_eff(u)| / (4 lambda) at the perturbed side.
    const double d = k.pinhole_m * p.side;
    s.v_per_px = d * k.pixel_pitch_m / (k.wavelength_m * k.sensor_distance_m);
    Camera kd = k;
    kd.pinhole_m = d;
    s.fresnel_n = fresnel_number_at_u(kd);
    // Mask centre (cell (N/2 - 1/2, N/2 - 1/2)) near the frame centre, off by a sub-pixel amount.
    const double t = p.rotation_deg * M_PI / 180.0;
    const double mc = 0.5 * (m.pattern.n * 2 - 1);
    const double cx = 0.5 * (c.cols - 1) + 0.37, cy = 0.5 * (c.rows - 1) - 0.21;
    s.x0 = cx - (s.pitch_x * std::cos(t) * mc + s.pitch_y * std::sin(t) * mc);
    s.y0 = cy - (-s.pitch_x * std::sin(t) * mc + s.pitch_y * std::cos(t) * mc);
    s.amplitude = p.flux > 0 ? p.flux : 800.0 * pitch * pitch;
    if (std::isfinite(p.optical_density))
        s.leak = std::pow(10.0, -p.optical_density) * s.amplitude / (s.pitch_x * s.pitch_y);
    s.dark = 20.0;
    s.photon_noise = true;
    s.read_noise_e = 3.0;
    s.adc_gain = 1.0;
    s.adc_bits = 16;
    s.seed = p.seed;
    // Missing pinholes: seeded picks among the open cells whose spot is well inside the frame.
    std::mt19937_64 rng(p.seed * 7919 + 3);
    std::vector<Cell> inside;
    for (const auto& [cell, xy] : spot_sites(s))
        if (xy.first > s.pitch_x && xy.second > s.pitch_y && xy.first < c.cols - 1 - s.pitch_x &&
            xy.second < c.rows - 1 - s.pitch_y)
            inside.push_back(cell);
    std::shuffle(inside.begin(), inside.end(), rng);
    for (int k2 = 0; k2 < p.missing && k2 < static_cast<int>(inside.size()); ++k2)
        s.missing.insert(inside[k2]);
    return s;
}

// Circular convolution with a full-frame PSF whose central element is the origin (deconvwnr).
inline Plane convolve_centred(const Plane& x, const Plane& psf) {
    const int r = static_cast<int>(x.rows()), c = static_cast<int>(x.cols());
    Fft2 fft(r, c);
    const ComplexPlane X = fft.forward(x), H = fft.forward(circshift(psf, -(r / 2), -(c / 2)));
    return fft.inverse((X * H).eval());
}

// PSNR at the best integer alignment within 6 px (a PSF's absolute position only shifts).
inline double aligned_psnr_db(const Plane& est, const Plane& truth) {
    double best = -1e300;
    for (int dr = -6; dr <= 6; ++dr)
        for (int dc = -6; dc <= 6; ++dc)
            best = std::max(best, psnr_db(circshift(est, dr, dc), truth));
    return best;
}

inline Plane smooth_scene(int rows, int cols, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Plane s = Plane::Zero(rows, cols);
    for (int k = 0; k < 40; ++k) {
        const double cy = u(rng) * rows, cx = u(rng) * cols, w = 2 + 10 * u(rng), a = u(rng);
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c)
                s(r, c) += a * std::exp(-((r - cy) * (r - cy) + (c - cx) * (c - cx)) / (2 * w * w));
    }
    return s / s.maxCoeff();
}

struct DecodeScores {
    double wiener_cal, wiener_design, wiener_true, tv_cal, tv_design, tv_true;
};

// A scene captured through the perturbed mask (the true PSF, 50 dB Gaussian noise), decoded
// with Wiener (NSR 1e-3) and TV (lambda 1e-3) using each PSF.
inline DecodeScores decode_scores(const Plane& cal_psf, const Plane& design_psf,
                                  const Plane& true_psf, unsigned seed) {
    const int rows = static_cast<int>(true_psf.rows()), cols = static_cast<int>(true_psf.cols());
    const Plane scene = smooth_scene(rows, cols, seed);
    Plane capture = convolve_centred(scene, true_psf);
    std::mt19937_64 rng(seed + 1);
    std::normal_distribution<double> nd(0.0, capture.maxCoeff() / std::pow(10.0, 50.0 / 20));
    for (auto& v : capture.reshaped()) v += nd(rng);
    DecodeOptions w;
    w.wiener.nsr = 1e-3;
    DecodeOptions tv;
    tv.method = DecodeMethod::kTv;
    tv.tv.lambda = 1e-3;
    tv.iterative.max_iterations = 100;
    tv.iterative.record_history = false;
    auto score = [&](const Plane& psf, const DecodeOptions& o) {
        return aligned_psnr_db(decode_plane(capture, psf, o).image, scene);
    };
    return {score(cal_psf, w),  score(design_psf, w),  score(true_psf, w),
            score(cal_psf, tv), score(design_psf, tv), score(true_psf, tv)};
}

}  // namespace pinmask::test
