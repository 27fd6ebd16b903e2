// The calibrated PSF decodes a scene captured through the perturbed mask better than the design
// PSF does (Wiener), in the demo's setting and at the edge of the tested range.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/fft/fft.hpp"
#include "decode/calibrate/calibrate.hpp"
#include "decode/capture/decoder.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/families.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "tests/decode/calibrate/point_source_model.hpp"

using namespace pinmask;

namespace {

// The required gain: the calibrated PSF beats the design PSF by at least this (Wiener PSNR).
constexpr double kMinGainDb = 2.0;

// Circular convolution of x with a PSF of x's size whose central element is the origin
// (deconvwnr convention), by FFT: the scene as the camera records it.
Plane convolve(const Plane& x, const Plane& psf) {
    const int r = static_cast<int>(x.rows()), c = static_cast<int>(x.cols());
    const Plane centred = circshift(psf, -(r / 2), -(c / 2));
    Fft2 fft(r, c);
    const ComplexPlane X = fft.forward(x), H = fft.forward(centred);
    return fft.inverse((X * H).eval());
}

// PSNR of the estimate against the truth at the best integer alignment (a PSF's absolute
// position only shifts the decoded image), over shifts of up to 8 pixels.
double aligned_psnr(const Plane& est, const Plane& truth) {
    double best = -1e300;
    for (int dr = -8; dr <= 8; ++dr)
        for (int dc = -8; dc <= 8; ++dc)
            best = std::max(best, psnr_db(circshift(est, dr, dc), truth));
    return best;
}

Plane smooth_scene(int rows, int cols, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Plane s = Plane::Zero(rows, cols);
    for (int k = 0; k < 40; ++k) {
        const double cy = u(rng) * rows, cx = u(rng) * cols, w = 3 + 12 * u(rng), a = u(rng);
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < cols; ++c)
                s(r, c) += a * std::exp(-((r - cy) * (r - cy) + (c - cx) * (c - cx)) / (2 * w * w));
    }
    return s / s.maxCoeff();
}

}  // namespace

TEST_CASE("calibrated PSF beats the design PSF by >= 2 dB (Wiener)") {
    std::mt19937_64 rng(21);
    Mask mask;
    mask.pattern = paper_pattern(rng);
    mask.camera = paper_camera();
    mask.psf.kernel.model = "box";
    struct Setting {
        double rotation_deg, pitch_scale;
        int missing;
        double snr_db;
        double nsr;  // Wiener NSR for both decodes (one value keeps the comparison fair): of the
                     // order of the noise power over the scene power at snr_db
    };
    for (const Setting st :
         {Setting{0.5, 1.005, 2, 40.0, 1e-4}, Setting{3.0, 1.02, 8, 20.0, 1e-3}}) {
        CAPTURE(st.rotation_deg);
        test::PointSourceScene s;
        s.pattern = mask.pattern;
        s.rows = s.cols = 300;
        s.rotation_deg = st.rotation_deg;
        s.pitch_x = s.pitch_y = 8.0 * st.pitch_scale;
        s.spot_px = s.pitch_x;
        s.x0 = 24.3;
        s.y0 = 25.6;
        s.snr_db = st.snr_db;
        s.leak = 2.0;
        std::set<Cell> all;
        for (const Cell& c : mask.pattern.pinholes) all.insert(c);
        auto it = all.begin();
        for (int k = 0; k < st.missing; ++k, ++it)
            s.missing.insert({it->row + (k % 2) * 16, it->col + (k / 2 % 2) * 16});
        const calibrate::CalibrationSummary cal =
            calibrate::calibrate_point_source(test::point_source_capture(s), std::nullopt, mask);

        // The design's full-frame PSF: every pinhole at the design pitch, no rotation, same origin.
        test::PointSourceScene d = s;
        d.rotation_deg = 0;
        d.pitch_x = d.pitch_y = 8.0;
        d.spot_px = 8.0;
        d.missing.clear();
        Plane design = test::point_source_spots(d);
        design /= design.sum();
        Plane truth_psf = test::point_source_spots(s);
        truth_psf /= truth_psf.sum();

        const Plane scene = smooth_scene(s.rows, s.cols, 5);
        Plane capture = convolve(scene, truth_psf);
        std::normal_distribution<double> noise(0.0,
                                               capture.maxCoeff() / std::pow(10, st.snr_db / 20));
        for (auto& v : capture.reshaped()) v += noise(rng);
        DecodeOptions o;
        o.wiener.nsr = st.nsr;
        const double p_design = aligned_psnr(decode_plane(capture, design, o).image, scene);
        const double p_cal =
            aligned_psnr(decode_plane(capture, cal.psfs.full_frame, o).image, scene);
        CAPTURE(p_design);
        CAPTURE(p_cal);
        CHECK(p_cal - p_design >= kMinGainDb);
    }
}
