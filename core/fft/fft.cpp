#include "core/fft/fft.hpp"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>

#include "core/errors/error.hpp"
#include "core/fft/fftw_api.hpp"
#include "core/fft/planning_notice.hpp"
#include "core/files/atomic_file.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask {
namespace {

enum class Kind { kR2C, kC2R, kC2CForward, kC2CBackward, kR2CF, kC2RF };

std::mutex& planner_mutex() {
    static std::mutex m;
    return m;
}

// Format 2: the header, then each precision's FFTW text after its section mark. A file of
// another format (format 1 marked its sections differently) is ignored and replaced, like a file
// of another FFTW version.
constexpr const char* kWisdomFamily = "pinmask-fftw-wisdom ";
constexpr const char* kWisdomMagic = "pinmask-fftw-wisdom 2";
constexpr const char* kDoubleMark = "[double]\n";
constexpr const char* kFloatMark = "[float]\n";

// The process-wide planner state and plan cache. Plans live until exit, when they are destroyed
// (and FFTW's own planner memory released) so leak checkers see a clean process.
struct PlanCache {
    std::map<std::tuple<Kind, int, int, int>, void*> plans;
    FftPlanner planner = FftPlanner::kEstimate;
    int threads = 1;
    std::string wisdom_path;
    std::function<void(int, int)> planning_notice;  // set_fft_planning_notice
    std::vector<std::string> warnings;
    FftPlanStats stats;
    PlanCache() {
        fftw_init_threads();
        fftwf_init_threads();
        fftw_set_timelimit(kFftPlanTimeLimitSeconds);
        fftwf_set_timelimit(kFftPlanTimeLimitSeconds);
    }
    ~PlanCache() {  // at exit, one thread left: no lock (the mutex may already be gone)
        for (auto& [key, plan] : plans) {
            const Kind k = std::get<0>(key);
            if (k == Kind::kR2CF || k == Kind::kC2RF) {
                fftwf_destroy_plan(static_cast<fftwf_plan>(plan));
            } else {
                fftw_destroy_plan(static_cast<fftw_plan>(plan));
            }
        }
        plans.clear();
        fftw_cleanup_threads();
        fftwf_cleanup_threads();
    }
};

PlanCache& cache_state() {
    static PlanCache cache;
    return cache;
}

std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) {
                std::string m = line.substr(colon + 1);
                m.erase(0, m.find_first_not_of(' '));
                return m;
            }
        }
    }
    return "unknown";
}

std::string header_text() {
    return std::string(kWisdomMagic) + "\nfftw " + fftw_version + "\ncpu " + cpu_model() + "\n";
}

std::string take_fftw_string(char* s) {
    std::string out = s ? s : "";
    free(s);  // NOLINT: FFTW allocates with malloc
    return out;
}

// Caller holds the planner mutex.
std::string wisdom_text_locked() {
    return header_text() + kDoubleMark + take_fftw_string(fftw_export_wisdom_to_string()) +
           kFloatMark + take_fftw_string(fftwf_export_wisdom_to_string());
}

// Splits trusted text into its two wisdom strings; returns the problem, or "" when trusted.
std::string split_wisdom(const std::string& text, std::string& dbl, std::string& flt) {
    const std::string header = header_text();
    if (text.rfind(kWisdomMagic, 0) != 0) {
        return text.rfind(kWisdomFamily, 0) == 0 ? "written in another pinmask wisdom format"
                                                 : "not a pinmask wisdom file";
    }
    if (text.rfind(header, 0) != 0) {
        return "written by another FFTW version or CPU (this process: " +
               std::string(fftw_version) + ", " + cpu_model() + ")";
    }
    const auto d = text.find(kDoubleMark, header.size());
    const auto f = text.find(kFloatMark, header.size());
    if (d != header.size() || f == std::string::npos || f < d) return "its sections are damaged";
    dbl = text.substr(d + std::strlen(kDoubleMark), f - d - std::strlen(kDoubleMark));
    flt = text.substr(f + std::strlen(kFloatMark));
    return "";
}

std::string read_text(const std::string& path, bool& exists) {
    std::ifstream in(path, std::ios::binary);
    exists = static_cast<bool>(in);
    std::ostringstream s;
    if (in) s << in.rdbuf();
    return s.str();
}

// Imports a trusted file into FFTW's wisdom; returns a warning or "". Caller holds the mutex.
std::string import_locked(const std::string& path) {
    bool exists = false;
    const std::string text = read_text(path, exists);
    if (!exists) return "";
    std::string dbl, flt;
    std::string problem = split_wisdom(text, dbl, flt);
    if (problem.empty()) {
        const bool ok = fftw_import_wisdom_from_string(dbl.c_str()) != 0 &&
                        fftwf_import_wisdom_from_string(flt.c_str()) != 0;
        if (!ok) {
            fftw_forget_wisdom();
            fftwf_forget_wisdom();
            problem = "FFTW could not parse it (corrupt)";
        }
    }
    return problem.empty() ? ""
                           : "FFT wisdom file " + path + " ignored: " + problem +
                                 "; it will be replaced by freshly measured plans";
}

// Merges the file's current wisdom (other processes may have added to it) and writes ours back.
void export_locked(PlanCache& c) {
    if (c.wisdom_path.empty()) return;
    try {
        (void)import_locked(c.wisdom_path);  // a bad file is simply replaced
        const std::filesystem::path p(c.wisdom_path);
        if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
        write_bytes_atomic(p, wisdom_text_locked());
    } catch (const std::exception& e) {
        c.warnings.push_back("FFT wisdom not saved to " + c.wisdom_path + ": " + e.what());
    }
}

bool threaded_size(int rows, int cols) {
    return static_cast<long long>(rows) * cols >= kFftThreadMinPixels;
}

bool is_float(Kind k) { return k == Kind::kR2CF || k == Kind::kC2RF; }

// One real-transform plan (r2c when forward, else c2r) in precision T on scratch buffers.
template <class T>
void* make_real_plan(bool forward, int rows, int cols, unsigned flags) {
    using F = Fftw<T>;
    T* re = F::alloc_real(static_cast<std::size_t>(rows) * cols);
    auto* cx = F::alloc_complex(static_cast<std::size_t>(rows) * (cols / 2 + 1));
    void* plan = forward ? F::r2c(rows, cols, re, cx, flags) : F::c2r(rows, cols, cx, re, flags);
    F::free(re);
    F::free(cx);
    return plan;
}

// What planning one transform allocates: the two scratch buffers of make_plan (FFTW's own
// working memory beside them is small: twiddle tables and row buffers). fftw_malloc failing
// ends the process inside FFTW ("alloc.c: assertion failed"), so the size is checked against
// the process-wide budget before planning.
double plan_bytes(Kind kind, int rows, int cols) {
    const double n = double(rows) * double(cols);
    const double half = double(rows) * double(cols / 2 + 1);
    switch (kind) {
        case Kind::kR2C:
        case Kind::kC2R:
            return n * sizeof(double) + half * 2.0 * sizeof(double);
        case Kind::kR2CF:
        case Kind::kC2RF:
            return n * sizeof(float) + half * 2.0 * sizeof(float);
        case Kind::kC2CForward:
        case Kind::kC2CBackward:
            break;
    }
    return 2.0 * n * 2.0 * sizeof(double);
}

// Makes one plan with `flags` on fftw_malloc'd scratch buffers (never the caller's data).
void* make_plan(Kind kind, int rows, int cols, unsigned flags) {
    switch (kind) {
        case Kind::kR2C:
        case Kind::kC2R:
            return make_real_plan<double>(kind == Kind::kR2C, rows, cols, flags);
        case Kind::kR2CF:
        case Kind::kC2RF:
            return make_real_plan<float>(kind == Kind::kR2CF, rows, cols, flags);
        case Kind::kC2CForward:
        case Kind::kC2CBackward: {
            const std::size_t n = static_cast<std::size_t>(rows) * cols;
            fftw_complex* in = fftw_alloc_complex(n);
            fftw_complex* out = fftw_alloc_complex(n);
            void* plan =
                fftw_plan_dft_2d(rows, cols, in, out,
                                 kind == Kind::kC2CForward ? FFTW_FORWARD : FFTW_BACKWARD, flags);
            fftw_free(in);
            fftw_free(out);
            return plan;
        }
    }
    return nullptr;
}

// Returns the cached plan for (kind, rows, cols, threads), creating it on first use. Execution
// uses the new-array interface, valid for buffers with the same SIMD alignment
// (fftw_alignment_of == 0). Eigen allocates 64-byte aligned buffers (EIGEN_MAX_ALIGN_BYTES in
// CMakeLists.txt); anything else goes through aligned copies, so one plan per size always runs
// and results do not depend on where a buffer happens to lie.
void* cached_plan(Kind kind, int rows, int cols) {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    const int threads = threaded_size(rows, cols) ? c.threads : 1;
    const auto key = std::make_tuple(kind, rows, cols, threads);
    if (auto it = c.plans.find(key); it != c.plans.end()) return it->second;

    check_memory(plan_bytes(kind, rows, cols),
                 "planning an FFT of " + std::to_string(rows) + " x " + std::to_string(cols));
    const auto t0 = std::chrono::steady_clock::now();
    if (is_float(kind)) {
        fftwf_plan_with_nthreads(threads);
    } else {
        fftw_plan_with_nthreads(threads);
    }
    const bool measure = c.planner == FftPlanner::kMeasure;
    void* plan = nullptr;
    bool from_wisdom = false;
    if (measure) {
        plan = make_plan(kind, rows, cols, FFTW_MEASURE | FFTW_WISDOM_ONLY);
        from_wisdom = plan != nullptr;
        if (!plan) {
            if (c.planning_notice) c.planning_notice(rows, cols);
            plan = make_plan(kind, rows, cols, FFTW_MEASURE);
        }
    } else {
        plan = make_plan(kind, rows, cols, FFTW_ESTIMATE);
    }
    if (plan == nullptr) {
        throw RuntimeFailure("FFTW could not create a plan for " + std::to_string(rows) + " x " +
                             std::to_string(cols));
    }
    c.plans.emplace(key, plan);
    ++c.stats.plans;
    if (from_wisdom) ++c.stats.plans_from_wisdom;
    if (measure && !from_wisdom) export_locked(c);
    c.stats.planning_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

std::string plan_size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

// r2c of x (rows x cols) into out (resized to the half spectrum), precision T.
template <class T, class PlaneT, class CPlaneT>
void real_forward(void* plan, int rows, int cols, const PlaneT& x, CPlaneT& out) {
    if (x.rows() != rows || x.cols() != cols) {
        throw InvalidInput("FFT input is " + plan_size_text(x.rows(), x.cols()) + ", plan is " +
                           plan_size_text(rows, cols));
    }
    out.resize(rows, cols / 2 + 1);
    // r2c with the default FFTW_PRESERVE_INPUT leaves the input untouched.
    with_aligned(const_cast<T*>(x.data()), static_cast<std::size_t>(x.size()), out.data(),
                 static_cast<std::size_t>(out.size()), [&](T* in, std::complex<T>* o) {
                     Fftw<T>::execute_r2c(plan, in,
                                          reinterpret_cast<typename Fftw<T>::Complex*>(o));
                 });
}

// c2r of spectrum (destroyed) into out, no 1/N, precision T.
template <class T, class PlaneT, class CPlaneT>
void real_inverse_destroy(void* plan, int rows, int cols, CPlaneT& spectrum, PlaneT& out) {
    if (spectrum.rows() != rows || spectrum.cols() != cols / 2 + 1) {
        throw InvalidInput("inverse FFT input is " +
                           plan_size_text(spectrum.rows(), spectrum.cols()) +
                           ", expected half spectrum " + plan_size_text(rows, cols / 2 + 1));
    }
    out.resize(rows, cols);
    with_aligned(spectrum.data(), static_cast<std::size_t>(spectrum.size()), out.data(),
                 static_cast<std::size_t>(out.size()), [&](std::complex<T>* in, T* o) {
                     Fftw<T>::execute_c2r(plan, reinterpret_cast<typename Fftw<T>::Complex*>(in),
                                          o);
                 });
}

}  // namespace

void set_fft_planning_notice(std::function<void(int rows, int cols)> notice) {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    c.planning_notice = std::move(notice);
}

void set_fft_planner(FftPlanner planner) {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    c.planner = planner;
}

FftPlanner fft_planner() {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    return c.planner;
}

void set_fft_threads(int threads) {
    if (threads < 1 || threads > 1024) {
        throw invalid_field("threads", std::to_string(threads), "must be 1..1024");
    }
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    c.threads = threads;
}

int fft_threads() {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    return c.threads;
}

int fft_threads_for(int rows, int cols) { return threaded_size(rows, cols) ? fft_threads() : 1; }

FftPlanStats fft_plan_stats() {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    return c.stats;
}

std::vector<std::string> set_fft_wisdom_file(const std::string& path) {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    c.wisdom_path = path;
    std::vector<std::string> out;
    if (path.empty()) return out;
    if (std::string w = import_locked(path); !w.empty()) out.push_back(w);
    return out;
}

std::string fft_wisdom_file() {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    return c.wisdom_path;
}

std::vector<std::string> take_fft_warnings() {
    PlanCache& c = cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    std::vector<std::string> out;
    out.swap(c.warnings);
    return out;
}

std::string fft_wisdom_text() {
    cache_state();
    std::lock_guard<std::mutex> lock(planner_mutex());
    return wisdom_text_locked();
}

std::string fft_wisdom_problem(const std::string& text) {
    std::string dbl, flt;
    return split_wisdom(text, dbl, flt);
}

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
    real_forward<double>(r2c_, rows_, cols_, x, out);
}

Plane Fft2::inverse(const ComplexPlane& spectrum) const {
    Plane out;
    ComplexPlane scratch;
    inverse(spectrum, out, scratch);
    return out;
}

void Fft2::inverse(const ComplexPlane& spectrum, Plane& out, ComplexPlane& scratch) const {
    scratch = spectrum;  // multi-dimensional c2r destroys its input
    inverse_unscaled_destroy(scratch, out);
    out *= 1.0 / (static_cast<double>(rows_) * cols_);  // the one place 1/N is applied
}

void Fft2::inverse_unscaled_destroy(ComplexPlane& spectrum, Plane& out) const {
    real_inverse_destroy<double>(c2r_, rows_, cols_, spectrum, out);
}

Fft2f::Fft2f(int rows, int cols) : rows_(rows), cols_(cols) {
    check_size(rows, cols);
    r2c_ = cached_plan(Kind::kR2CF, rows, cols);
    c2r_ = cached_plan(Kind::kC2RF, rows, cols);
}

void Fft2f::forward(const PlaneF& x, ComplexPlaneF& out) const {
    real_forward<float>(r2c_, rows_, cols_, x, out);
}

void Fft2f::inverse(const ComplexPlaneF& spectrum, PlaneF& out, ComplexPlaneF& scratch) const {
    scratch = spectrum;
    inverse_unscaled_destroy(scratch, out);
    out *= static_cast<float>(1.0 / (static_cast<double>(rows_) * cols_));
}

void Fft2f::inverse_unscaled_destroy(ComplexPlaneF& spectrum, PlaneF& out) const {
    real_inverse_destroy<float>(c2r_, rows_, cols_, spectrum, out);
}

FftC2::FftC2(int rows, int cols) : rows_(rows), cols_(cols) {
    check_size(rows, cols);
    fwd_ = cached_plan(Kind::kC2CForward, rows, cols);
    bwd_ = cached_plan(Kind::kC2CBackward, rows, cols);
}

namespace {

ComplexPlane execute_c2c(void* plan, const ComplexPlane& x, int rows, int cols) {
    if (x.rows() != rows || x.cols() != cols) {
        throw InvalidInput("complex FFT input is " + plan_size_text(x.rows(), x.cols()) +
                           ", plan is " + plan_size_text(rows, cols));
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
