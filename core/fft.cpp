#include "core/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

#include "core/error.hpp"

namespace pinmask {
namespace {

enum class Kind { kR2C, kC2R, kC2CForward, kC2CBackward };

std::mutex& planner_mutex() {
    static std::mutex m;
    return m;
}

// Returns the cached plan for (kind, rows, cols), creating it on first use. Planning happens on
// fftw_malloc'd scratch buffers; execution uses the new-array interface, valid for buffers with
// the same SIMD alignment (fftw_alignment_of == 0). Eigen allocates 64-byte aligned buffers
// (EIGEN_MAX_ALIGN_BYTES in CMakeLists.txt); anything else goes through aligned copies, so one
// plan per size always runs and results do not depend on where a buffer happens to lie.
// The process-wide plan cache. Plans live until exit, when they are destroyed (and FFTW's own
// planner memory released) so leak checkers see a clean process.
struct PlanCache {
    std::map<std::tuple<Kind, int, int>, fftw_plan> plans;
    ~PlanCache() {  // at exit, one thread left: no lock (the mutex may already be gone)
        for (auto& [key, plan] : plans) fftw_destroy_plan(plan);
        plans.clear();
        fftw_cleanup();
    }
};

fftw_plan cached_plan(Kind kind, int rows, int cols) {
    static PlanCache plan_cache;
    auto& cache = plan_cache.plans;
    std::lock_guard<std::mutex> lock(planner_mutex());
    const auto key = std::make_tuple(kind, rows, cols);
    if (auto it = cache.find(key); it != cache.end()) return it->second;

    const std::size_t n_real = static_cast<std::size_t>(rows) * cols;
    const std::size_t n_half = static_cast<std::size_t>(rows) * (cols / 2 + 1);
    const unsigned flags = FFTW_ESTIMATE;
    fftw_plan plan = nullptr;
    switch (kind) {
        case Kind::kR2C: {
            double* in = fftw_alloc_real(n_real);
            fftw_complex* out = fftw_alloc_complex(n_half);
            plan = fftw_plan_dft_r2c_2d(rows, cols, in, out, flags);
            fftw_free(in);
            fftw_free(out);
            break;
        }
        case Kind::kC2R: {
            fftw_complex* in = fftw_alloc_complex(n_half);
            double* out = fftw_alloc_real(n_real);
            plan = fftw_plan_dft_c2r_2d(rows, cols, in, out, flags);
            fftw_free(in);
            fftw_free(out);
            break;
        }
        case Kind::kC2CForward:
        case Kind::kC2CBackward: {
            fftw_complex* in = fftw_alloc_complex(n_real);
            fftw_complex* out = fftw_alloc_complex(n_real);
            plan =
                fftw_plan_dft_2d(rows, cols, in, out,
                                 kind == Kind::kC2CForward ? FFTW_FORWARD : FFTW_BACKWARD, flags);
            fftw_free(in);
            fftw_free(out);
            break;
        }
    }
    if (plan == nullptr) {
        throw RuntimeFailure("FFTW could not create a plan for " + std::to_string(rows) + " x " +
                             std::to_string(cols));
    }
    cache.emplace(key, plan);
    return plan;
}

void check_size(int rows, int cols) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("FFT size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
}

fftw_complex* as_fftw(std::complex<double>* p) { return reinterpret_cast<fftw_complex*>(p); }

bool aligned(const void* p) {
    return fftw_alignment_of(reinterpret_cast<double*>(const_cast<void*>(p))) == 0;
}

// Runs `execute(in, out)` on FFTW-aligned buffers, copying through aligned temporaries when the
// caller's buffers are not (never the case for Eigen arrays built by this project).
template <class In, class Out, class F>
void with_aligned(In* in, std::size_t n_in, Out* out, std::size_t n_out, F&& execute) {
    if (aligned(in) && aligned(out)) {
        execute(in, out);
        return;
    }
    In* a = static_cast<In*>(fftw_malloc(sizeof(In) * n_in));
    Out* b = static_cast<Out*>(fftw_malloc(sizeof(Out) * n_out));
    std::copy(in, in + n_in, a);
    execute(a, b);
    std::copy(b, b + n_out, out);
    fftw_free(a);
    fftw_free(b);
}

}  // namespace

Fft2::Fft2(int rows, int cols) : rows_(rows), cols_(cols) {
    check_size(rows, cols);
    r2c_ = cached_plan(Kind::kR2C, rows, cols);
    c2r_ = cached_plan(Kind::kC2R, rows, cols);
}

ComplexPlane Fft2::forward(const Plane& x) const {
    ComplexPlane out;
    forward(x, out);
    return out;
}

void Fft2::forward(const Plane& x, ComplexPlane& out) const {
    if (x.rows() != rows_ || x.cols() != cols_) {
        throw InvalidInput("FFT input is " + std::to_string(x.rows()) + " x " +
                           std::to_string(x.cols()) + ", plan is " + std::to_string(rows_) + " x " +
                           std::to_string(cols_));
    }
    out.resize(rows_, half_cols());
    // r2c with the default FFTW_PRESERVE_INPUT leaves the input untouched.
    with_aligned(const_cast<double*>(x.data()), static_cast<std::size_t>(x.size()), out.data(),
                 static_cast<std::size_t>(out.size()), [&](double* in, std::complex<double>* o) {
                     fftw_execute_dft_r2c(static_cast<fftw_plan>(r2c_), in, as_fftw(o));
                 });
}

Plane Fft2::inverse(const ComplexPlane& spectrum) const {
    Plane out;
    ComplexPlane scratch;
    inverse(spectrum, out, scratch);
    return out;
}

void Fft2::inverse(const ComplexPlane& spectrum, Plane& out, ComplexPlane& scratch) const {
    if (spectrum.rows() != rows_ || spectrum.cols() != half_cols()) {
        throw InvalidInput("inverse FFT input is " + std::to_string(spectrum.rows()) + " x " +
                           std::to_string(spectrum.cols()) + ", expected half spectrum " +
                           std::to_string(rows_) + " x " + std::to_string(half_cols()));
    }
    scratch = spectrum;  // multi-dimensional c2r destroys its input
    out.resize(rows_, cols_);
    with_aligned(scratch.data(), static_cast<std::size_t>(scratch.size()), out.data(),
                 static_cast<std::size_t>(out.size()), [&](std::complex<double>* in, double* o) {
                     fftw_execute_dft_c2r(static_cast<fftw_plan>(c2r_), as_fftw(in), o);
                 });
    out *= 1.0 / (static_cast<double>(rows_) * cols_);  // the one place 1/N is applied
}

FftC2::FftC2(int rows, int cols) : rows_(rows), cols_(cols) {
    check_size(rows, cols);
    fwd_ = cached_plan(Kind::kC2CForward, rows, cols);
    bwd_ = cached_plan(Kind::kC2CBackward, rows, cols);
}

namespace {

ComplexPlane execute_c2c(void* plan, const ComplexPlane& x, int rows, int cols) {
    if (x.rows() != rows || x.cols() != cols) {
        throw InvalidInput("complex FFT input is " + std::to_string(x.rows()) + " x " +
                           std::to_string(x.cols()) + ", plan is " + std::to_string(rows) + " x " +
                           std::to_string(cols));
    }
    ComplexPlane in = x, out(rows, cols);
    const auto n = static_cast<std::size_t>(in.size());
    with_aligned(in.data(), n, out.data(), n,
                 [&](std::complex<double>* a, std::complex<double>* b) {
                     fftw_execute_dft(static_cast<fftw_plan>(plan), as_fftw(a), as_fftw(b));
                 });
    return out;
}

}  // namespace

ComplexPlane FftC2::forward(const ComplexPlane& x) const {
    return execute_c2c(fwd_, x, rows_, cols_);
}

ComplexPlane FftC2::inverse(const ComplexPlane& x) const {
    ComplexPlane out = execute_c2c(bwd_, x, rows_, cols_);
    out *= 1.0 / (static_cast<double>(rows_) * cols_);
    return out;
}

ComplexPlane expand_half_spectrum(const ComplexPlane& half, int cols) {
    const Eigen::Index rows = half.rows();
    ComplexPlane full(rows, cols);
    const int hc = cols / 2 + 1;
    for (Eigen::Index k = 0; k < rows; ++k) {
        for (int l = 0; l < cols; ++l) {
            if (l < hc) {
                full(k, l) = half(k, l);
            } else {
                full(k, l) = std::conj(half((rows - k) % rows, cols - l));
            }
        }
    }
    return full;
}

}  // namespace pinmask
