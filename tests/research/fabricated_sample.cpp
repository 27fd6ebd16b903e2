#include "tests/research/fabricated_sample.hpp"

#include <cmath>
#include <functional>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "decode/solvers/wiener.hpp"
#include "design/psf/psf.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/simulate.hpp"

namespace pinmask {

FabricationSampler::FabricationSampler(const Mask& mask, FabricationErrors errors,
                                       const KernelOptions& options)
    : mask_(mask), errors_(errors), kernels_(fabricated_kernels(mask, errors, options)) {
    if (mask.pattern.pinholes.empty()) {
        throw InvalidInput("fabricated PSF: the pattern has no pinholes");
    }
    check_psf_memory(mask.pattern.n, mask.psf.pixels_per_cell, 2, 0);
    sigma_px_ = jitter_sigma_px(mask, errors);
    m_ = mask.pattern.n * mask.psf.pixels_per_cell;
}

Plane FabricationSampler::draw(std::mt19937_64& rng) const {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::normal_distribution<double> normal(0.0, sigma_px_ > 0.0 ? sigma_px_ : 1.0);
    const Kernel& k = kernels_.size() == 2 && !(uniform(rng) < 0.5) ? kernels_[1] : kernels_[0];
    const int ppc = mask_.psf.pixels_per_cell, m = m_;
    const double weight =
        1.0 / ((1.0 - errors_.missing) * static_cast<double>(mask_.pattern.pinholes.size()));
    Plane psf = Plane::Zero(m, m);
    const auto wrap = [m](long long v) { return static_cast<Eigen::Index>(((v % m) + m) % m); };
    for (const Cell& c : mask_.pattern.pinholes) {
        if (errors_.missing > 0.0 && uniform(rng) < errors_.missing) continue;
        double dr = 0.0, dc = 0.0;
        if (sigma_px_ > 0.0) {
            dr = normal(rng);
            dc = normal(rng);
        }
        const double sr = std::floor(dr), sc = std::floor(dc), fr = dr - sr, fc = dc - sc;
        const long long r0 =
            static_cast<long long>(c.row) * ppc + k.origin_row + static_cast<long long>(sr);
        const long long c0 =
            static_cast<long long>(c.col) * ppc + k.origin_col + static_cast<long long>(sc);
        const double w[2][2] = {{(1 - fr) * (1 - fc), (1 - fr) * fc}, {fr * (1 - fc), fr * fc}};
        for (Eigen::Index i = 0; i < k.values.rows(); ++i)
            for (Eigen::Index j = 0; j < k.values.cols(); ++j) {
                const double v = weight * k.values(i, j);
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b)
                        psf(wrap(r0 + i + a), wrap(c0 + j + b)) += w[a][b] * v;
            }
    }
    return psf;
}

namespace {

using Decode = std::function<void(const Plane& capture, Plane& estimate)>;

// The loop shared by the Wiener and frequency-response decoders (contract in the header).
FabricatedQuality fabricated_quality(const Mask& mask, const FabricationErrors& errors,
                                     const std::vector<NamedScene>& scenes, const NoiseModel& noise,
                                     int draws, std::uint64_t seed, const Decode& decode) {
    const FabricationSampler sampler(mask, errors);
    const int m = sampler.period();
    const Plane nominal = mask_psf(mask);
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const int cells = mask.pattern.n * mask.pattern.n;
    FabricatedQuality q;
    q.draws = draws;
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const Image& img = scenes[s].image;
        if (img.rows() != m || img.cols() != m) {
            throw InvalidInput("fabricated quality: scene '" + scenes[s].name +
                               "' does not have the period size " + std::to_string(m));
        }
        double sum_nominal = 0.0, sum_fabricated = 0.0;
        int count = 0;
        for (int d = 0; d < draws; ++d) {
            std::seed_seq seq{static_cast<std::uint32_t>(seed),
                              static_cast<std::uint32_t>(seed >> 32),
                              static_cast<std::uint32_t>(d)};
            std::mt19937_64 psf_rng(seq);
            const Plane fabricated = sampler.draw(psf_rng);
            for (int ch = 0; ch < img.n_channels(); ++ch) {
                const Plane& truth = img.channels[ch];
                for (const bool nominal_psf : {true, false}) {
                    std::seed_seq noise_seq{
                        static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(s),
                        static_cast<std::uint32_t>(d), static_cast<std::uint32_t>(ch), 7u};
                    std::mt19937_64 noise_rng(noise_seq);  // the same noise for both PSFs
                    const Plane& psf = nominal_psf ? nominal : fabricated;
                    // Every pinhole missing: no light reaches the sensor.
                    const Plane clean =
                        psf.sum() > 0.0 ? cyclic_capture(truth, psf) : Plane(Plane::Zero(m, m));
                    const Plane noisy = add_noise(clean, noise, holes, cells, noise_rng);
                    Plane x;
                    decode(noisy, x);
                    (nominal_psf ? sum_nominal : sum_fabricated) += mse(x, truth);
                }
                ++count;
            }
        }
        q.nominal_psnr_db += psnr_from_mse(sum_nominal / count) / scenes.size();
        q.fabricated_psnr_db += psnr_from_mse(sum_fabricated / count) / scenes.size();
    }
    return q;
}

void check_quality_args(const std::vector<NamedScene>& scenes, const NoiseModel& noise, int draws) {
    if (draws < 1) throw invalid_field("draws", std::to_string(draws), "must be >= 1");
    if (scenes.empty()) throw InvalidInput("fabricated quality: no scenes");
    validate(noise);
}

}  // namespace

FabricatedQuality fabricated_wiener_quality(const Mask& mask, const FabricationErrors& errors,
                                            const std::vector<NamedScene>& scenes,
                                            const NoiseModel& noise, double nsr, int draws,
                                            std::uint64_t seed) {
    check_quality_args(scenes, noise, draws);
    const Plane nominal = mask_psf(mask);
    const int m = static_cast<int>(nominal.rows());
    const WienerFilter filter(nominal, m, m, nsr);
    WienerFilter::Workspace ws;
    return fabricated_quality(mask, errors, scenes, noise, draws, seed,
                              [&](const Plane& c, Plane& x) { filter.apply(c, x, ws); });
}

FabricatedQuality fabricated_filter_quality(const Mask& mask, const FabricationErrors& errors,
                                            const std::vector<NamedScene>& scenes,
                                            const NoiseModel& noise, const ComplexPlane& response,
                                            int draws, std::uint64_t seed) {
    check_quality_args(scenes, noise, draws);
    const int m = mask.pattern.n * mask.psf.pixels_per_cell;
    if (response.rows() != m || response.cols() != m) {
        throw InvalidInput("fabricated quality: the filter response is " +
                           std::to_string(response.rows()) + " x " +
                           std::to_string(response.cols()) + ", the period " + std::to_string(m));
    }
    const FftC2 fft(m, m);
    // The captures are centred as the decoder's (psf2otf moves the PSF's central element to the
    // origin): C^ = R X^ H with R that shift's transfer; G applies in design/psf/psf's frame.
    Plane delta = Plane::Zero(m, m);
    delta(0, 0) = 1.0;
    const ComplexPlane shift = fft.forward(psf_to_origin(delta, m, m).cast<std::complex<double>>());
    const ComplexPlane g = response * shift.conjugate();
    return fabricated_quality(
        mask, errors, scenes, noise, draws, seed, [&](const Plane& c, Plane& x) {
            const ComplexPlane spectrum = fft.forward(c.cast<std::complex<double>>());
            x = fft.inverse(g * spectrum).real();
        });
}

}  // namespace pinmask
