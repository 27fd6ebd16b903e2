#include "optimize/metrics/simulated_metrics.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/psf2otf.hpp"
#include "decode/solvers/wiener.hpp"
#include "optimize/metrics/nsr_tuning.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

void check_weight(const char* field, const WeightChoice& w) {
    if (!w.tuned && (!(w.value > 0.0) || !std::isfinite(w.value))) {
        throw invalid_field(field, std::to_string(w.value), "must be finite and > 0 (or tuned)");
    }
}

// One noisy capture of one channel of one scene; when the Wiener NSR is tuned also both half
// spectra, so tuning needs no transform (wiener_mse).
struct Trial {
    int scene = 0;
    const Plane* truth = nullptr;
    Plane capture;
    const ComplexPlane* truth_spectrum = nullptr;
    ComplexPlane capture_spectrum;
};

// The MSE of the Wiener estimate real(ifft2(G .* fft2(capture))) against the truth, by Parseval
// from the half spectra: (1 / N^2) sum_full |G Y - X|^2 with N = rows cols. G is Hermitian (a
// real PSF, a scalar NSR), so G Y is the estimate's spectrum exactly; the decoded MSE is the
// same number up to rounding (tests/optimize/metrics/test_simulated_metrics.cpp).
double wiener_mse(const ComplexPlane& g, const Plane& multiplicity, const Trial& t) {
    const double n = static_cast<double>(t.truth->size());
    const double sum = (multiplicity * (g * t.capture_spectrum - *t.truth_spectrum).abs2()).sum();
    return sum / (n * n);
}

}  // namespace

void SimulatedMetricsOptions::validate() const {
    if (noise_seeds < 1 || noise_seeds > kMaxNoiseSeeds) {
        throw invalid_field(field_ref("noise_seeds"), std::to_string(noise_seeds),
                            "must be between 1 and 1000 (noise realisations per scene)");
    }
    check_weight("wiener_nsr", wiener_nsr);
    check_weight("tv_lambda", tv_lambda);
    if (tv_iterations < 1) {
        throw invalid_field("tv_iterations", std::to_string(tv_iterations), "must be >= 1");
    }
    if (!(tv_tolerance >= 0.0)) {
        throw invalid_field("tv_tolerance", std::to_string(tv_tolerance), "must be >= 0");
    }
}

SimulatedQuality simulated_quality(const Plane& psf, const std::vector<NamedScene>& scenes,
                                   double snr_db, SimulatedDecoder decoder,
                                   const SimulatedMetricsOptions& options) {
    NoiseModel noise;
    noise.kind = NoiseKind::kGaussianSnr;
    noise.snr_db = snr_db;
    return simulated_quality(psf, scenes, noise, 1, 1, decoder, options);
}

SimulatedQuality simulated_quality(const Plane& psf, const std::vector<NamedScene>& scenes,
                                   const NoiseModel& noise, int open_cells, int total_cells,
                                   SimulatedDecoder decoder,
                                   const SimulatedMetricsOptions& options) {
    options.validate();
    if (scenes.empty()) throw InvalidInput("simulated metrics: no scenes");
    if (psf.size() == 0 || !psf.isFinite().all() || !(psf.sum() > 0.0)) {
        throw InvalidInput("simulated metrics: the PSF must be non-empty, finite, with sum > 0");
    }
    const int rows = static_cast<int>(psf.rows()), cols = static_cast<int>(psf.cols());
    const Fft2 fft(rows, cols);
    const ComplexPlane otf = psf2otf(psf, rows, cols);
    validate(noise);
    if (noise.kind == NoiseKind::kPhoton && !(open_cells >= 1 && total_cells >= open_cells))
        throw InvalidInput("simulated metrics: the photon model needs 1 <= open cells (" +
                           std::to_string(open_cells) + ") <= total cells (" +
                           std::to_string(total_cells) + ")");

    const bool wiener = decoder == SimulatedDecoder::kWiener;
    // Tuning the Wiener NSR works on spectra (wiener_mse); a given NSR needs none of them.
    const bool parseval_tuning = wiener && options.wiener_nsr.tuned;
    std::vector<Trial> trials;
    std::vector<ComplexPlane> truth_spectra;  // one per scene channel, for parseval_tuning
    std::vector<int> per_scene(scenes.size(), 0);
    std::size_t channels = 0;
    for (const NamedScene& s : scenes) channels += static_cast<std::size_t>(s.image.n_channels());
    truth_spectra.reserve(channels);  // the trials point into it
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const Image& img = scenes[s].image;
        if (img.rows() != rows || img.cols() != cols || img.n_channels() < 1) {
            throw InvalidInput("simulated metrics: scene '" + scenes[s].name + "' is " +
                               size_text(img.rows(), img.cols()) + ", the period is " +
                               size_text(rows, cols));
        }
        for (int ch = 0; ch < img.n_channels(); ++ch) {
            ComplexPlane truth_spectrum = fft.forward(img.channels[ch]);
            const Plane clean = fft.inverse(truth_spectrum * otf);
            if (parseval_tuning) truth_spectra.push_back(std::move(truth_spectrum));
            for (int k = 0; k < options.noise_seeds; ++k) {
                std::seed_seq seq{static_cast<std::uint32_t>(options.seed),
                                  static_cast<std::uint32_t>(options.seed >> 32),
                                  static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(ch),
                                  static_cast<std::uint32_t>(k)};
                std::mt19937_64 rng(seq);
                Trial t{static_cast<int>(s),
                        &img.channels[ch],
                        add_noise(clean, noise, open_cells, total_cells, rng),
                        nullptr,
                        {}};
                if (parseval_tuning) {
                    t.truth_spectrum = &truth_spectra.back();
                    t.capture_spectrum = fft.forward(t.capture);
                }
                trials.push_back(std::move(t));
                ++per_scene[s];
            }
        }
    }

    SimulatedQuality q;
    // Decodes every trial with weight w.
    auto decode_all = [&](double w) {
        std::vector<Plane> out;
        out.reserve(trials.size());
        if (wiener) {
            const WienerFilter filter = WienerFilter::from_otf(otf, rows, cols, w);
            WienerFilter::Workspace ws;
            for (const Trial& t : trials) {
                Plane x;
                filter.apply(t.capture, x, ws);
                out.push_back(std::move(x));
            }
        } else {
            DecodeOptions o;
            o.method = DecodeMethod::kTv;
            o.model = ConvModel::kCyclic;
            o.tv.lambda = w;
            o.iterative.max_iterations = options.tv_iterations;
            o.iterative.tolerance = options.tv_tolerance;
            o.iterative.record_history = false;
            for (const Trial& t : trials) out.push_back(decode_plane(t.capture, psf, o).image);
        }
        q.decodes += static_cast<long long>(trials.size());
        return out;
    };
    const Plane multiplicity = parseval_tuning ? half_spectrum_multiplicity(rows, cols) : Plane();
    auto mean_mse = [&](double w) {
        double sum = 0.0;
        if (parseval_tuning) {  // no transform per weight: Parseval on the stored spectra
            const WienerFilter filter = WienerFilter::from_otf(otf, rows, cols, w);
            for (const Trial& t : trials)
                sum += wiener_mse(filter.half_spectrum(), multiplicity, t);
            return sum / static_cast<double>(trials.size());
        }
        const std::vector<Plane> est = decode_all(w);
        for (std::size_t i = 0; i < trials.size(); ++i) sum += mse(est[i], *trials[i].truth);
        return sum / static_cast<double>(trials.size());
    };
    const WeightChoice& choice = wiener ? options.wiener_nsr : options.tv_lambda;
    q.weight = choice.tuned ? tune_log_weight(mean_mse).x : choice.value;

    const std::vector<Plane> est = decode_all(q.weight);
    const bool has_ssim = rows >= kSsimWindow && cols >= kSsimWindow;
    std::vector<double> mse_sum(scenes.size(), 0.0), ssim_sum(scenes.size(), 0.0);
    for (std::size_t i = 0; i < trials.size(); ++i) {
        mse_sum[trials[i].scene] += mse(est[i], *trials[i].truth);
        if (has_ssim) ssim_sum[trials[i].scene] += ssim(est[i], *trials[i].truth);
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        SceneQuality sq;
        sq.scene = scenes[s].name;
        sq.psnr_db = psnr_from_mse(mse_sum[s] / per_scene[s]);
        sq.ssim = has_ssim ? ssim_sum[s] / per_scene[s] : nan;
        q.mean_psnr_db += sq.psnr_db / static_cast<double>(scenes.size());
        q.mean_ssim += sq.ssim / static_cast<double>(scenes.size());
        q.scenes.push_back(sq);
    }
    return q;
}

}  // namespace pinmask
