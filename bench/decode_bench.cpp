#include "bench/decode_bench.hpp"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "core/error.hpp"
#include "decode/convolution.hpp"
#include "decode/richardson_lucy.hpp"
#include "decode/tikhonov.hpp"
#include "decode/tv_l2.hpp"
#include "decode/tvqc.hpp"
#include "decode/wiener.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

// Noise of the synthetic capture, relative to its mean (sets TVQC's eps).
constexpr double kNoiseRelative = 0.01;
// Iterations added to measure one iteration as a difference (amortises the solver's setup).
constexpr int kExtraIterations = 10;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Minimum over `repeat` batches of the per-call time of fn; a batch repeats fn until it lasts
// min_batch seconds (calibrated once).
double time_per_call(const std::function<void()>& fn, int repeat, double min_batch) {
    auto t0 = Clock::now();
    fn();
    const double once = std::max(seconds_since(t0), 1e-9);
    const int calls = std::max(1, static_cast<int>(std::ceil(min_batch / once)));
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < repeat; ++r) {
        t0 = Clock::now();
        for (int i = 0; i < calls; ++i) fn();
        best = std::min(best, seconds_since(t0) / calls);
    }
    return best;
}

// A coded-aperture-like PSF: 20 square pinhole spots of side n / 32 at seeded positions.
Plane make_psf(int n, std::mt19937_64& rng) {
    const int spot = std::max(1, n / 32);
    std::uniform_int_distribution<int> pos(0, n - spot);
    Plane psf = Plane::Zero(n, n);
    for (int k = 0; k < 20; ++k) psf.block(pos(rng), pos(rng), spot, spot) += 1.0;
    return psf / psf.sum();
}

// A scene of seeded rectangles of random brightness on a dark background.
Plane make_scene(int n, std::mt19937_64& rng) {
    std::uniform_int_distribution<int> pos(0, n / 2), len(n / 16, n / 2);
    std::uniform_real_distribution<double> level(0.2, 1.0);
    Plane x = Plane::Constant(n, n, 0.05);
    for (int k = 0; k < 12; ++k) x.block(pos(rng), pos(rng), len(rng), len(rng)) = level(rng);
    return x;
}

// The bare FFTW r2c + c2r pair on FFTW-allocated buffers (same planner flags as core/fft).
double time_fft_pair(int n, int repeat, double min_batch) {
    const std::size_t real = static_cast<std::size_t>(n) * n;
    const std::size_t half = static_cast<std::size_t>(n) * (n / 2 + 1);
    double* x = fftw_alloc_real(real);
    fftw_complex* spec = fftw_alloc_complex(half);
    fftw_plan r2c = fftw_plan_dft_r2c_2d(n, n, x, spec, FFTW_ESTIMATE);
    fftw_plan c2r = fftw_plan_dft_c2r_2d(n, n, spec, x, FFTW_ESTIMATE);
    for (std::size_t i = 0; i < real; ++i) x[i] = static_cast<double>(i % 97) / 97.0;
    const double t = time_per_call(
        [&] {
            fftw_execute(r2c);
            fftw_execute(c2r);
        },
        repeat, min_batch);
    fftw_destroy_plan(r2c);
    fftw_destroy_plan(c2r);
    fftw_free(spec);
    fftw_free(x);
    return t;
}

void validate(const DecodeBenchOptions& o) {
    if (o.sizes.empty()) throw invalid_field("sizes", "empty", "give at least one size");
    for (int n : o.sizes) {
        if (n < 16 || n > 8192) throw invalid_field("sizes", std::to_string(n), "must be 16..8192");
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    if (!(o.min_batch_seconds > 0.0)) {
        throw invalid_field("min_batch_seconds", std::to_string(o.min_batch_seconds),
                            "must be > 0");
    }
    if (o.tvqc_max_iterations < 1) {
        throw invalid_field("tvqc_max_iterations", std::to_string(o.tvqc_max_iterations),
                            "must be >= 1");
    }
}

}  // namespace

std::vector<DecodeBenchRecord> bench_decode(const DecodeBenchOptions& o) {
    validate(o);
    std::vector<DecodeBenchRecord> out;
    std::mt19937_64 rng(o.seed);
    for (int n : o.sizes) {
        const Plane psf = make_psf(n, rng);
        const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, n, n, n, n);
        const ConvolutionOperator op(psf, g);
        Plane p = op.apply(make_scene(n, rng));
        const double sigma = kNoiseRelative * p.mean();
        std::normal_distribution<double> noise(0.0, sigma);
        for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] += noise(rng);

        const double pair = time_fft_pair(n, o.repeat, o.min_batch_seconds);
        auto add = [&](const char* method, double t, int iterations = 1, bool converged = true) {
            out.push_back({method, n, t, pair, t / pair, iterations, converged});
        };

        const WienerFilter wiener(psf, n, n, 0.01);
        WienerFilter::Workspace ws;
        Plane x;
        add("wiener",
            time_per_call([&] { wiener.apply(p, x, ws); }, o.repeat, o.min_batch_seconds));

        const WienerFilter tik =
            make_tikhonov_filter(psf, n, n, 0.01, TikhonovRegulariser::kGradient);
        add("tikhonov", time_per_call([&] { tik.apply(p, x, ws); }, o.repeat, o.min_batch_seconds));

        // One iteration as the difference of a (1 + m)-iteration and a 1-iteration run.
        auto per_iteration = [&](const std::function<void(int)>& solve) {
            const double t1 = time_per_call([&] { solve(1); }, o.repeat, o.min_batch_seconds);
            const double tm =
                time_per_call([&] { solve(1 + kExtraIterations); }, o.repeat, o.min_batch_seconds);
            // Under load the difference of two noisy timings can vanish; then the plain average
            // over the longer run (which includes the set-up once) bounds it from above.
            return tm > t1 ? (tm - t1) / kExtraIterations : tm / (1 + kExtraIterations);
        };
        TvL2Options tv;
        tv.lambda = 0.01 * sigma;
        tv.tolerance = 0.0;
        tv.record_history = false;
        add("tv_l2_iteration", per_iteration([&](int iters) {
                tv.max_iterations = iters;
                solve_tv_l2(op, p, tv);
            }));

        TvqcOptions qc;
        qc.eps = tvqc_eps_from_sigma(sigma, p.size());
        qc.max_iterations = o.tvqc_max_iterations;
        qc.tolerance = 1e-4;
        qc.record_history = false;
        // One whole run, timed once: it lasts many FFT pairs, long enough to be stable.
        const auto t0 = Clock::now();
        const DecodeResult last = solve_tvqc(op, p, qc);
        const double t_qc = seconds_since(t0);
        add("tvqc_to_tolerance", t_qc, last.iterations, last.converged);

        RichardsonLucyOptions rl;
        rl.tolerance = 0.0;
        rl.record_history = false;
        add("rl_iteration", per_iteration([&](int iters) {
                rl.max_iterations = iters;
                solve_richardson_lucy(op, psf, p, rl);
            }));
    }
    return out;
}

}  // namespace pinmask
