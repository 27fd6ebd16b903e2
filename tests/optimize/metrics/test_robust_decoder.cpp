// The robust filter as an ordinary Wiener decode (RobustWienerModel::robust_decoder_inputs, what
// `score --robust-decoder` writes and `decode --psf ... --nsr-map ...` reads): decode's Wiener
// with the expected fabricated PSF and the per-frequency NSR is the robust filter G of
// robust_filter_response, by the closed-form identity
//     conj(E T) S / (E|T|^2 S + N sigma^2) = conj(E T) / (|E T|^2 + NSR).
// Reference: robust_filter_response applied by the test's own FFTs (a second code path), in
// decode's frame (psf2otf moves the PSF's centre to the origin: the response times the
// conjugate of that shift's transfer, as fabricated_filter_quality applies it).
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/fft/fft.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "design/optics/camera.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "tests/support/random_pattern.hpp"

namespace pinmask {
namespace {

constexpr double kIdentityTolerance = 1e-12;  // relative to the largest value compared

ComplexPlane full_fft(const Plane& x) {
    return FftC2(static_cast<int>(x.rows()), static_cast<int>(x.cols()))
        .forward(x.cast<std::complex<double>>());
}

// x = real(ifft2(G conj(shift) fft2(c))): the response applied in decode's frame.
Plane apply_response(const ComplexPlane& g, const Plane& c) {
    const int m = static_cast<int>(c.rows());
    Plane delta = Plane::Zero(m, m);
    delta(0, 0) = 1.0;
    const ComplexPlane shift = full_fft(psf_to_origin(delta, m, m));
    const ComplexPlane spectrum = full_fft(c);
    const ComplexPlane filtered = g * shift.conjugate() * spectrum;
    return FftC2(m, m).inverse(filtered).real();
}

double max_abs(const Plane& x) { return x.abs().maxCoeff(); }

}  // namespace

TEST_CASE("robust decoder inputs: decode's Wiener with them is the robust filter") {
    const int n = 8, m = 64;
    const ScenePrior prior = natural_scene_prior(m, m, 4, 1000, 1.0);
    struct Case {
        std::string name;
        FabricationErrors errors;
        double snr_db;
    };
    const std::vector<Case> cases{{"size, jitter, missing at 25 dB", {60e-6, 30e-6, 0.05}, 25.0},
                                  {"size and jitter at 50 dB", {44e-6, 2e-6, 0.0}, 50.0},
                                  {"no errors at 30 dB", {}, 30.0}};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    Plane capture(m, m);
    for (Eigen::Index i = 0; i < capture.size(); ++i) capture.data()[i] = uniform(rng);
    for (const Case& c : cases) {
        CAPTURE(c.name);
        const Mask mask = test::random_paper_mask(n, 6, 3);
        NoiseModel noise;
        noise.snr_db = c.snr_db;
        const RobustWienerModel model(mask, c.errors, prior, noise);
        const ComplexPlane p = pattern_spectrum(mask.pattern);
        const RobustDecoderInputs in = model.robust_decoder_inputs(p);
        REQUIRE(in.psf.rows() == m);
        REQUIRE(in.nsr.rows() == m);
        CHECK(in.floored == 0);
        CHECK(std::abs(in.psf.sum() - 1.0) <= kIdentityTolerance);
        CHECK(in.psf.minCoeff() >= -kIdentityTolerance * in.psf.maxCoeff());
        CHECK(in.nsr.minCoeff() > 0.0);
        CHECK(is_all_finite(in.nsr));

        // The filters themselves: conj(H) / (|H|^2 + NSR) with H = decode's OTF of the PSF.
        const ComplexPlane g = model.robust_filter_response(p);
        Plane delta = Plane::Zero(m, m);
        delta(0, 0) = 1.0;
        const ComplexPlane shift = full_fft(psf_to_origin(delta, m, m));
        const ComplexPlane h = full_fft(psf_to_origin(in.psf, m, m));
        double filter_error = 0.0;
        for (Eigen::Index i = 0; i < h.size(); ++i) {
            const std::complex<double> wiener =
                std::conj(h.data()[i]) / (std::norm(h.data()[i]) + in.nsr.data()[i]);
            filter_error =
                std::max(filter_error, std::abs(wiener - g.data()[i] * std::conj(shift.data()[i])));
        }
        const double g_max = g.abs().maxCoeff();
        CAPTURE(filter_error);
        CAPTURE(g_max);
        CHECK(filter_error <= kIdentityTolerance * g_max);

        // decode_plane (the library decode the CLI runs) with the map: the same estimate.
        DecodeOptions o;
        o.wiener.nsr_per_frequency = in.nsr;
        const Plane x = decode_plane(capture, in.psf, o).image;
        const Plane reference = apply_response(g, capture);
        const double decode_error = max_abs(x - reference);
        CAPTURE(decode_error);
        CHECK(decode_error <= kIdentityTolerance * max_abs(reference));

        if (!c.errors.any()) {
            // Without errors the expected PSF is the design's and the NSR the noise's alone.
            CHECK(max_abs(in.psf - mask_psf(mask)) <= kIdentityTolerance * max_abs(in.psf));
        }
    }
}

TEST_CASE("robust decoder inputs: where the prior has no power the NSR is the no-signal value") {
    const int n = 8, m = 64;
    ScenePrior prior = natural_scene_prior(m, m, 4, 1000, 1.0);
    prior.power(3, 5) = 0.0;
    NoiseModel noise;
    noise.snr_db = 30.0;
    const Mask mask = test::random_paper_mask(n, 6, 3);
    const RobustWienerModel model(mask, {44e-6, 2e-6, 0.0}, prior, noise);
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    const RobustDecoderInputs in = model.robust_decoder_inputs(p);
    CHECK(in.nsr(3, 5) == kRobustNsrNoSignal);
    CHECK(model.robust_filter_response(p)(3, 5) == std::complex<double>(0.0, 0.0));
    CHECK(in.nsr(4, 5) < kRobustNsrNoSignal);
}

}  // namespace pinmask
