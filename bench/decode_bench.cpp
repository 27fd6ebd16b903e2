#include "bench/decode_bench.hpp"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/fft/fftw_api.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/richardson_lucy.hpp"
#include "decode/solvers/tikhonov.hpp"
#include "decode/solvers/tv_l2.hpp"
#include "decode/solvers/tvqc.hpp"
#include "decode/solvers/wiener.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

// Noise of the synthetic capture, relative to its mean (sets TVQC's eps).
constexpr double kNoiseRelative = 0.01;
// Iterations added to measure one iteration as a difference (amortises the solver's setup).
constexpr int kExtraIterations = 10;

// Wall time (steady clock) or the calling thread's CPU time (CLOCK_THREAD_CPUTIME_ID), seconds.
struct BenchClock {
    bool cpu = false;
    double now() const {
        if (cpu) {
            timespec ts{};
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
            return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
        }
        return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
    }
};

// Minimum over `repeat` batches of the per-call time of fn; a batch repeats fn until it lasts
// min_batch seconds (calibrated once).
double time_per_call(const std::function<void()>& fn, int repeat, double min_batch,
                     const BenchClock& clock) {
    double t0 = clock.now();
    fn();
    const double once = std::max(clock.now() - t0, 1e-9);
    const int calls = std::max(1, static_cast<int>(std::ceil(min_batch / once)));
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < repeat; ++r) {
        t0 = clock.now();
        for (int i = 0; i < calls; ++i) fn();
        best = std::min(best, (clock.now() - t0) / calls);
    }
    return best;
}

// One iteration as the difference of a (1 + m)-iteration and a 1-iteration run of `solve`.
double time_per_iteration(const std::function<void(int)>& solve, int repeat, double min_batch,
                          const BenchClock& clock) {
    const double t1 = time_per_call([&] { solve(1); }, repeat, min_batch, clock);
    const double tm = time_per_call([&] { solve(1 + kExtraIterations); }, repeat, min_batch, clock);
    // Under load the difference of two noisy timings can vanish; then the plain average over the
    // longer run (which includes the set-up once) bounds it from above.
    return tm > t1 ? (tm - t1) / kExtraIterations : tm / (1 + kExtraIterations);
}

// A lensless-camera-like PSF spread over its whole rows x cols support: seeded bright points
// (about 1 % of the pixels, random weights), sum 1.
Plane make_spread_psf(int rows, int cols, std::mt19937_64& rng) {
    std::uniform_int_distribution<int> r(0, rows - 1), c(0, cols - 1);
    std::uniform_real_distribution<double> weight(0.2, 1.0);
    Plane psf = Plane::Zero(rows, cols);
    const int points = std::max(1, rows * cols / 100);
    for (int k = 0; k < points; ++k) psf(r(rng), c(rng)) += weight(rng);
    return psf / psf.sum();
}

// A rows x cols scene of seeded rectangles of random brightness on a dark background.
Plane make_scene_rect(int rows, int cols, std::mt19937_64& rng) {
    std::uniform_int_distribution<int> pr(0, rows / 2), pc(0, cols / 2);
    std::uniform_int_distribution<int> lr(std::max(1, rows / 16), std::max(1, rows / 2));
    std::uniform_int_distribution<int> lc(std::max(1, cols / 16), std::max(1, cols / 2));
    std::uniform_real_distribution<double> level(0.2, 1.0);
    Plane x = Plane::Constant(rows, cols, 0.05);
    for (int k = 0; k < 12; ++k) x.block(pr(rng), pc(rng), lr(rng), lc(rng)) = level(rng);
    return x;
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

// The bare FFTW r2c + c2r pair on FFTW-allocated buffers, planned with FFTW_MEASURE (the
// planner times candidates: the fastest pair FFTW offers on this machine) with `threads`.
template <class Real>
double time_fft_pair(int rows, int cols, int repeat, double min_batch, int threads,
                     const BenchClock& clock) {
    using F = Fftw<Real>;
    const std::size_t real = static_cast<std::size_t>(rows) * cols;
    const std::size_t half = static_cast<std::size_t>(rows) * (cols / 2 + 1);
    Real* x = F::alloc_real(real);
    auto* spec = F::alloc_complex(half);
    F::plan_with_nthreads(threads);
    auto r2c = F::r2c(rows, cols, x, spec, FFTW_MEASURE);
    auto c2r = F::c2r(rows, cols, spec, x, FFTW_MEASURE);
    for (std::size_t i = 0; i < real; ++i) x[i] = static_cast<Real>(i % 97) / Real(97);
    const double t = time_per_call(
        [&] {
            F::execute(r2c);
            F::execute(c2r);
        },
        repeat, min_batch, clock);
    F::destroy(r2c);
    F::destroy(c2r);
    F::free(spec);
    F::free(x);
    return t;
}

// The paper's PSF at N = 16 n_px: 20 pinholes on a 16 x 16 cell grid (seeded, no two in one
// cell), each an n_px x n_px box (the geometric kernel), sum 1.
Plane make_paper_psf(int n, std::mt19937_64& rng) {
    const int cell = n / 16;
    std::vector<int> cells(256);
    for (int i = 0; i < 256; ++i) cells[i] = i;
    std::shuffle(cells.begin(), cells.end(), rng);
    Plane psf = Plane::Zero(n, n);
    for (int k = 0; k < 20; ++k)
        psf.block((cells[k] / 16) * cell, (cells[k] % 16) * cell, cell, cell) = 1.0;
    return psf / psf.sum();
}

double psnr(const Plane& x, const Plane& ref) {
    const double mse = (x - ref).square().mean();
    const double peak = ref.maxCoeff();
    return 10.0 * std::log10(peak * peak / std::max(mse, 1e-300));
}

}  // namespace

TvConvergence tv_l2_iterations_to_converged(int n, double lambda, double snr_db, double within_db,
                                            int max_iterations, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const Plane psf = make_paper_psf(n, rng);
    const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, n, n, n, n);
    const ConvolutionOperator op(psf, g);
    const Plane scene = make_scene(n, rng);
    Plane p = op.apply(scene);
    const double sigma = std::sqrt(p.square().mean()) * std::pow(10.0, -snr_db / 20.0);
    std::normal_distribution<double> noise(0.0, sigma);
    for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] += noise(rng);
    TvL2Options tv;
    tv.lambda = lambda;
    tv.record_history = false;
    tv.tolerance = 1e-9;
    tv.max_iterations = 5000;
    TvConvergence out;
    out.converged_psnr_db = psnr(solve_tv_l2(op, p, tv).image, scene);
    tv.tolerance = 0.0;
    // The last iteration count k <= max_iterations whose PSNR is outside the band, plus one.
    int last_outside = 0;
    for (int k = 1; k <= max_iterations; ++k) {
        tv.max_iterations = k;
        const double q = psnr(solve_tv_l2(op, p, tv).image, scene);
        if (std::abs(q - out.converged_psnr_db) > within_db) last_outside = k;
        if (k == 1) out.first_psnr_db = q;
    }
    out.iterations = last_outside + 1;
    out.reached = last_outside < max_iterations;
    return out;
}

namespace {

void validate(const DecodeBenchOptions& o) {
    if (o.sizes.empty() && o.shapes.empty())
        throw invalid_field("sizes", "empty", "give at least one size");
    for (int n : o.sizes) {
        if (n < 16 || n > 8192) throw invalid_field("sizes", std::to_string(n), "must be 16..8192");
    }
    for (auto [r, c] : o.shapes) {
        if (r < 16 || r > 8192 || c < 16 || c > 8192) {
            throw invalid_field("shapes", std::to_string(r) + "x" + std::to_string(c),
                                "each side must be 16..8192");
        }
    }
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    if (!(o.min_batch_seconds > 0.0)) {
        throw invalid_field("min_batch_seconds", std::to_string(o.min_batch_seconds),
                            "must be > 0");
    }
    if (o.threads < 1 || o.threads > 1024) {
        throw invalid_field("threads", std::to_string(o.threads), "must be 1..1024");
    }
    if (o.cpu_time && o.threads != 1) {
        throw invalid_field("cpu_time", "with threads " + std::to_string(o.threads),
                            "CPU time counts the calling thread only: use threads = 1");
    }
    if (o.tvqc_max_iterations < 1) {
        throw invalid_field("tvqc_max_iterations", std::to_string(o.tvqc_max_iterations),
                            "must be >= 1");
    }
}

}  // namespace

std::vector<DecodeBenchRecord> bench_decode(const DecodeBenchOptions& o) {
    validate(o);
    // The run's thread count, restored however the run ends.
    struct ThreadsScope {
        int saved = fft_threads();
        explicit ThreadsScope(int t) { set_fft_threads(t); }
        ~ThreadsScope() { set_fft_threads(saved); }
    } threads_scope(o.threads);
    BenchClock clock;
    clock.cpu = o.cpu_time;
    std::vector<DecodeBenchRecord> out;
    std::mt19937_64 rng(o.seed);
    std::vector<std::pair<int, int>> shapes;
    for (int n : o.sizes) shapes.emplace_back(n, n);
    shapes.insert(shapes.end(), o.shapes.begin(), o.shapes.end());
    for (const auto& shape : shapes) {
        const int rows = shape.first, cols = shape.second;  // named: lambdas capture them
        const int n = std::min(rows, cols);
        Plane psf = Plane::Zero(rows, cols);
        psf.block((rows - n) / 2, (cols - n) / 2, n, n) = make_psf(n, rng);
        const ConvGeometry g = make_conv_geometry(ConvModel::kCyclic, rows, cols, rows, cols);
        const ConvolutionOperator op(psf, g);
        Plane scene = Plane::Constant(rows, cols, 0.05);
        scene.block((rows - n) / 2, (cols - n) / 2, n, n) = make_scene(n, rng);
        Plane p = op.apply(scene);
        const double sigma = kNoiseRelative * p.mean();
        std::normal_distribution<double> noise(0.0, sigma);
        for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] += noise(rng);

        const int threads = fft_threads_for(rows, cols);  // what the library's plans use
        const double pair =
            time_fft_pair<double>(rows, cols, o.repeat, o.min_batch_seconds, threads, clock);
        const double pair_f =
            time_fft_pair<float>(rows, cols, o.repeat, o.min_batch_seconds, threads, clock);
        auto add = [&](const char* method, int fft_pairs, double t, int iterations = 1,
                       bool converged = true) {
            DecodeBenchRecord rec;
            rec.method = method;
            rec.size = rows;
            rec.cols = cols;
            rec.seconds_per_call = t;
            rec.fft_pair_seconds = pair;
            rec.ratio = t / pair;
            rec.fft_pair_float_seconds = pair_f;
            rec.ratio_float = t / pair_f;
            rec.iterations = iterations;
            rec.converged = converged;
            rec.fft_pairs = fft_pairs;
            out.push_back(rec);
        };

        const WienerFilter wiener(psf, rows, cols, 0.01);
        WienerFilter::Workspace ws;
        WienerFilter::WorkspaceF wsf;
        Plane x;
        add("wiener", 1,
            time_per_call([&] { wiener.apply(p, x, ws); }, o.repeat, o.min_batch_seconds, clock));
        add("wiener_single", 1,
            time_per_call([&] { wiener.apply_single(p, x, wsf); }, o.repeat, o.min_batch_seconds,
                          clock));

        const WienerFilter tik =
            make_tikhonov_filter(psf, rows, cols, 0.01, TikhonovRegulariser::kGradient);
        add("tikhonov", 1,
            time_per_call([&] { tik.apply(p, x, ws); }, o.repeat, o.min_batch_seconds, clock));

        auto per_iteration = [&](const std::function<void(int)>& solve) {
            return time_per_iteration(solve, o.repeat, o.min_batch_seconds, clock);
        };
        TvL2Options tv;
        tv.lambda = 0.01 * sigma;
        tv.tolerance = 0.0;
        tv.record_history = false;
        add("tv_l2_iteration", 1, per_iteration([&](int iters) {
                tv.max_iterations = iters;
                solve_tv_l2(op, p, tv);
            }));
        tv.single_precision = true;
        add("tv_l2_iteration_single", 1, per_iteration([&](int iters) {
                tv.max_iterations = iters;
                solve_tv_l2(op, p, tv);
            }));
        tv.single_precision = false;
        if (rows == cols && rows % 16 == 0 && rows <= 256) {
            const TvConvergence c =
                tv_l2_iterations_to_converged(rows, 1e-3, 30.0, 0.2, 40, o.seed);
            TvL2Options t2;
            t2.lambda = 1e-3;
            t2.tolerance = 0.0;
            t2.record_history = false;
            t2.max_iterations = c.iterations;
            add("tv_l2_to_0.2dB", 0,
                time_per_call([&] { solve_tv_l2(op, p, t2); }, o.repeat, o.min_batch_seconds,
                              clock),
                c.iterations, c.reached);
        }

        TvqcOptions qc;
        qc.eps = tvqc_eps_from_sigma(sigma, p.size());
        qc.max_iterations = o.tvqc_max_iterations;
        qc.tolerance = 1e-4;
        qc.record_history = false;
        // One whole run, timed once: it lasts many FFT pairs, long enough to be stable.
        const double t0 = clock.now();
        const DecodeResult last = solve_tvqc(op, p, qc);
        const double t_qc = clock.now() - t0;
        add("tvqc_to_tolerance", 0, t_qc, last.iterations, last.converged);
        qc.max_iterations = 1 + kExtraIterations;
        add("tvqc_iteration", 2, per_iteration([&](int iters) {
                qc.max_iterations = iters;
                qc.tolerance = 0.0;
                solve_tvqc(op, p, qc);
            }));
        qc.single_precision = true;
        add("tvqc_iteration_single", 2, per_iteration([&](int iters) {
                qc.max_iterations = iters;
                qc.tolerance = 0.0;
                solve_tvqc(op, p, qc);
            }));

        RichardsonLucyOptions rl;
        rl.tolerance = 0.0;
        rl.record_history = false;
        add("rl_iteration", 2, per_iteration([&](int iters) {
                rl.max_iterations = iters;
                solve_richardson_lucy(op, psf, p, rl);
            }));
        rl.single_precision = true;
        add("rl_iteration_single", 2, per_iteration([&](int iters) {
                rl.max_iterations = iters;
                solve_richardson_lucy(op, psf, p, rl);
            }));

        if (!o.linear) continue;
        // Linear model: this shape is the working grid of a capture of half its size and a PSF
        // of the other half (capture + PSF - 1 = the shape per axis).
        const int cap_r = rows / 2, cap_c = cols / 2;
        const Plane lpsf = make_spread_psf(rows + 1 - cap_r, cols + 1 - cap_c, rng);
        const ConvGeometry lg = make_conv_geometry(ConvModel::kLinear, cap_r, cap_c,
                                                   int(lpsf.rows()), int(lpsf.cols()));
        const ConvolutionOperator lop(lpsf, lg);
        Plane lscene = Plane::Constant(lg.work_rows, lg.work_cols, 0.05);
        lscene.block(lg.crop_row, lg.crop_col, cap_r, cap_c) = make_scene_rect(cap_r, cap_c, rng);
        Plane lp = lop.apply(lscene);
        const double lsigma = kNoiseRelative * lp.mean();
        std::normal_distribution<double> lnoise(0.0, lsigma);
        for (Eigen::Index i = 0; i < lp.size(); ++i) lp.data()[i] += lnoise(rng);
        // The pairs of the working grid (the shape itself unless it is not 2^a 3^b 5^c 7^d).
        double lpair = pair, lpair_f = pair_f;
        if (lg.work_rows != rows || lg.work_cols != cols) {
            const int lt = fft_threads_for(lg.work_rows, lg.work_cols);
            lpair = time_fft_pair<double>(lg.work_rows, lg.work_cols, o.repeat, o.min_batch_seconds,
                                          lt, clock);
            lpair_f = time_fft_pair<float>(lg.work_rows, lg.work_cols, o.repeat,
                                           o.min_batch_seconds, lt, clock);
        }
        auto add_linear = [&](const char* method, int fft_pairs, double t) {
            DecodeBenchRecord rec;
            rec.method = method;
            rec.model = "linear";
            rec.size = lg.work_rows;
            rec.cols = lg.work_cols;
            rec.seconds_per_call = t;
            rec.fft_pair_seconds = lpair;
            rec.ratio = t / lpair;
            rec.fft_pair_float_seconds = lpair_f;
            rec.ratio_float = t / lpair_f;
            rec.iterations = 1;
            rec.fft_pairs = fft_pairs;
            out.push_back(rec);
        };
        TvL2Options ltv;
        ltv.lambda = 1e-4 * lp.abs().maxCoeff();
        ltv.nonnegative = true;
        ltv.single_precision = true;
        ltv.tolerance = 0.0;
        ltv.record_history = false;
        add_linear("tv_l2_linear_iteration_single", 2, per_iteration([&](int iters) {
                       ltv.max_iterations = iters;
                       solve_tv_l2(lop, lp, ltv);
                   }));
        TvqcOptions lqc;
        lqc.eps = tvqc_eps_from_sigma(lsigma, lp.size());
        lqc.nonnegative = true;
        lqc.single_precision = true;
        lqc.tolerance = 0.0;
        lqc.record_history = false;
        add_linear("tvqc_linear_iteration_single", 2, per_iteration([&](int iters) {
                       lqc.max_iterations = iters;
                       solve_tvqc(lop, lp, lqc);
                   }));
        RichardsonLucyOptions lrl;
        lrl.single_precision = true;
        lrl.tolerance = 0.0;
        lrl.record_history = false;
        add_linear("rl_linear_iteration_single", 2, per_iteration([&](int iters) {
                       lrl.max_iterations = iters;
                       solve_richardson_lucy(lop, lpsf, lp, lrl);
                   }));
    }
    return out;
}

}  // namespace pinmask
