#include "bench/error_time.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/units/number_format.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/tvqc.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/simulate.hpp"

namespace pinmask {
namespace {

void check_list_nonnegative(const std::vector<double>& v, const char* field) {
    for (double x : v) {
        if (!(x >= 0.0) || !std::isfinite(x)) {
            throw invalid_field(field, format_number(x), "every value must be finite and >= 0");
        }
    }
}

// SplitMix64: decorrelated 64-bit seeds for the capture of scene s at SNR index k.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t s, std::uint64_t k) {
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (1 + s * 0x10001ULL + k * 0x100000001ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One scene's noisy capture at one SNR, with the per-channel noise sigma TVQC needs.
struct NoisyCapture {
    Image capture;
    std::vector<double> sigma;
};

struct Setting {
    std::string decoder, parameter;
    double value = 0.0;
    int iterations = 0;
    DecodeOptions options;
};

std::vector<Setting> settings(const ErrorTimeOptions& o) {
    std::vector<Setting> out;
    for (double nsr : o.wiener_nsr) {
        Setting s{"wiener", "nsr", nsr, 0, {}};
        s.options.method = DecodeMethod::kWiener;
        s.options.wiener.nsr = nsr;
        out.push_back(s);
    }
    for (double lambda : o.tikhonov_lambda) {
        Setting s{"tikhonov", "lambda", lambda, 0, {}};
        s.options.method = DecodeMethod::kTikhonov;
        s.options.tikhonov.regulariser = TikhonovRegulariser::kGradient;
        s.options.tikhonov.lambda = lambda;
        out.push_back(s);
    }
    const std::pair<const char*, DecodeMethod> iterative[] = {
        {"tv-l2", DecodeMethod::kTv},
        {"tvqc", DecodeMethod::kTvqc},
        {"richardson-lucy", DecodeMethod::kRichardsonLucy}};
    for (const auto& [name, method] : iterative) {
        for (int k : o.iterations) {
            Setting s{name, "", 0.0, k, {}};
            s.options.method = method;
            s.options.iterative.max_iterations = k;
            s.options.iterative.tolerance = 0.0;  // exactly k iterations
            if (method == DecodeMethod::kTv) {
                s.parameter = "lambda";
                s.value = o.tv_lambda;
                s.options.tv.lambda = o.tv_lambda;
            } else if (method == DecodeMethod::kTvqc) {
                s.parameter = "eps";
            }
            out.push_back(s);
        }
    }
    for (Setting& s : out) {
        s.options.model = ConvModel::kCyclic;
        s.options.iterative.record_history = false;
    }
    return out;
}

}  // namespace

void ErrorTimeOptions::validate() const {
    if (snr_db.empty()) throw invalid_field("snr_db", "[]", "needs at least one SNR");
    for (double s : snr_db) {
        if (!std::isfinite(s)) throw invalid_field("snr_db", format_number(s), "must be finite");
    }
    for (int k : iterations) {
        if (k < 1) throw invalid_field("iterations", std::to_string(k), "every count must be >= 1");
    }
    check_list_nonnegative(wiener_nsr, "wiener_nsr");
    check_list_nonnegative(tikhonov_lambda, "tikhonov_lambda");
    if (!(tv_lambda > 0.0) || !std::isfinite(tv_lambda)) {
        throw invalid_field("tv_lambda", format_number(tv_lambda), "must be finite and > 0");
    }
    if (repeats < 1) throw invalid_field("repeats", std::to_string(repeats), "must be >= 1");
    if (!(repeat_below_seconds >= 0.0)) {
        throw invalid_field("repeat_below_seconds", format_number(repeat_below_seconds),
                            "must be >= 0");
    }
}

std::vector<ErrorTimeRecord> run_error_time(const Plane& psf, const std::vector<NamedScene>& scenes,
                                            const ErrorTimeOptions& options) {
    options.validate();
    if (scenes.empty()) throw InvalidInput("error-time: no scenes");
    for (const NamedScene& s : scenes) {
        if (s.image.rows() != psf.rows() || s.image.cols() != psf.cols()) {
            throw InvalidInput("error-time: scene '" + s.name + "' is " +
                               std::to_string(s.image.rows()) + " x " +
                               std::to_string(s.image.cols()) + ", the period is " +
                               std::to_string(psf.rows()) + " x " + std::to_string(psf.cols()));
        }
    }
    using Clock = std::chrono::steady_clock;
    const std::vector<Setting> all = settings(options);
    const bool has_ssim = psf.rows() >= kSsimWindow && psf.cols() >= kSsimWindow;
    // Warm-up, not timed: FFTW plans of this size are made once per process (core/fft/fft.hpp),
    // which would otherwise be charged to whichever point runs first.
    {
        const Plane& x = scenes[0].image.channels[0];
        for (const Setting& st : all) {
            if (st.iterations > 1) continue;
            DecodeOptions o = st.options;
            if (o.method == DecodeMethod::kTvqc) o.tvqc.noise_sigma = 1e-3;
            decode_plane(x, psf, o);
        }
    }
    std::vector<ErrorTimeRecord> out;
    for (std::size_t k = 0; k < options.snr_db.size(); ++k) {
        for (std::size_t si = 0; si < scenes.size(); ++si) {
            const Image& truth = scenes[si].image;
            SimulationOptions sim;
            sim.noise.kind = NoiseKind::kGaussianSnr;
            sim.noise.snr_db = options.snr_db[k];
            sim.seed = mix_seed(options.seed, si, k);
            NoisyCapture cap;
            const SimulatedCapture s = simulate_capture(truth, psf, 1, 1, sim);
            cap.capture = s.capture;
            for (const Plane& clean : s.clean.channels) {
                cap.sigma.push_back(sigma_for_snr(clean.square().mean(), options.snr_db[k]));
            }
            for (const Setting& st : all) {
                if (options.progress) {
                    std::ostringstream msg;
                    msg << "snr " << options.snr_db[k] << " dB, " << scenes[si].name << ", "
                        << st.decoder;
                    if (!st.parameter.empty() && st.decoder != "tvqc")
                        msg << " " << st.parameter << " " << st.value;
                    if (st.iterations > 0) msg << ", " << st.iterations << " iterations";
                    options.progress(msg.str());
                }
                ErrorTimeRecord r;
                r.snr_db = options.snr_db[k];
                r.scene = scenes[si].name;
                r.decoder = st.decoder;
                r.parameter = st.parameter;
                r.value = st.value;
                r.iterations = st.iterations;
                Image estimate;
                std::vector<double> times, walls;
                // One decode of every channel: records its CPU and wall-clock seconds.
                auto decode_all = [&]() {
                    Image est;
                    int run = 0;
                    bool converged = true;
                    const auto t0 = Clock::now();
                    const double c0 = thread_cpu_seconds();
                    for (int ch = 0; ch < cap.capture.n_channels(); ++ch) {
                        DecodeOptions o = st.options;
                        if (o.method == DecodeMethod::kTvqc) o.tvqc.noise_sigma = cap.sigma[ch];
                        DecodeResult d = decode_plane(cap.capture.channels[ch], psf, o);
                        run = std::max(run, d.iterations);
                        converged = converged && d.converged;
                        est.channels.push_back(std::move(d.image));
                    }
                    times.push_back(thread_cpu_seconds() - c0);
                    walls.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
                    r.iterations_run = run;
                    r.converged = converged;
                    estimate = std::move(est);
                };
                decode_all();
                if (times[0] < options.repeat_below_seconds) {
                    while (static_cast<int>(times.size()) < options.repeats) decode_all();
                }
                r.seconds = median(times);
                r.wall_seconds = median(walls);
                r.timing_runs = static_cast<int>(times.size());
                if (st.decoder == "tvqc") {
                    r.value = tvqc_eps_from_sigma(cap.sigma[0], cap.capture.channels[0].size());
                }
                r.psnr_db = psnr_db(estimate, truth);
                r.ssim =
                    has_ssim ? ssim(estimate, truth) : std::numeric_limits<double>::quiet_NaN();
                out.push_back(r);
            }
        }
    }
    return out;
}

std::vector<ErrorTimePoint> mean_over_scenes(const std::vector<ErrorTimeRecord>& records) {
    std::vector<ErrorTimePoint> out;
    for (const ErrorTimeRecord& r : records) {
        const bool closed = r.iterations == 0;
        auto it = std::find_if(out.begin(), out.end(), [&](const ErrorTimePoint& p) {
            return p.snr_db == r.snr_db && p.decoder == r.decoder && p.parameter == r.parameter &&
                   p.iterations == r.iterations && (!closed || p.value == r.value);
        });
        if (it == out.end()) {
            ErrorTimePoint p;
            p.snr_db = r.snr_db;
            p.decoder = r.decoder;
            p.parameter = r.parameter;
            p.iterations = r.iterations;
            out.push_back(p);
            it = out.end() - 1;
        }
        it->value += r.value;
        it->seconds += r.seconds;
        it->wall_seconds += r.wall_seconds;
        it->psnr_db += r.psnr_db;
        it->ssim += r.ssim;
        ++it->scenes;
    }
    for (ErrorTimePoint& p : out) {
        p.value /= p.scenes;
        p.seconds /= p.scenes;
        p.wall_seconds /= p.scenes;
        p.psnr_db /= p.scenes;
        p.ssim /= p.scenes;
    }
    return out;
}

std::vector<DecoderSummary> summarise_decoders(const std::vector<ErrorTimePoint>& points,
                                               double tol_db) {
    std::vector<DecoderSummary> out;
    auto same = [](const ErrorTimePoint& a, const ErrorTimePoint& b) {
        return a.snr_db == b.snr_db && a.decoder == b.decoder;
    };
    for (const ErrorTimePoint& p : points) {
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const DecoderSummary& d) { return same(d.best, p); });
        if (it == out.end()) {
            out.push_back({p, p});
        } else if (p.psnr_db > it->best.psnr_db ||
                   (p.psnr_db == it->best.psnr_db && p.seconds < it->best.seconds)) {
            it->best = p;
        }
    }
    for (DecoderSummary& d : out) {
        d.near_best = d.best;
        if (d.best.iterations == 0) continue;
        for (const ErrorTimePoint& p : points) {
            if (same(p, d.best) && p.psnr_db >= d.best.psnr_db - tol_db &&
                p.seconds < d.near_best.seconds) {
                d.near_best = p;
            }
        }
    }
    return out;
}

}  // namespace pinmask
