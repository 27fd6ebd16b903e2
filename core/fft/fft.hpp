// FFT wrapper over FFTW3 (double and single precision). Conventions, written down once for the
// project:
//
//   forward  X[k, l] = sum_{r, c} x[r, c] exp(-2 pi i (k r / R + l c / C))      (unnormalised)
//   inverse  x[r, c] = 1/(R C) sum_{k, l} X[k, l] exp(+2 pi i (k r / R + l c / C))
//
// The 1/(R C) factor is applied in inverse() and nowhere else, so forward followed by inverse is
// the identity. Layout is row-major (Eigen RowMajor == FFTW's C order). Real transforms use the
// half spectrum: an R x C real plane maps to R x (C/2 + 1) complex coefficients, the columns
// l = 0 .. C/2; the rest follow from Hermitian symmetry X[k, l] = conj(X[-k, -l]).
//
// Plans are made once per (kind, precision, size, threads), cached for the life of the process,
// and created under one mutex, so Fft2 objects may be constructed and used from any thread.
// Executing a plan is thread-safe. Plans are SIMD-aligned; Eigen buffers are 64-byte aligned
// project-wide (CMakeLists.txt), and other buffers are copied through aligned temporaries, so
// results never depend on buffer addresses.
//
// Planning (process-wide, set by the caller; the libraries' default is kEstimate, no wisdom):
// - kEstimate: FFTW_ESTIMATE, no timing: the same plan in every run (deterministic).
// - kMeasure: FFTW_MEASURE (each candidate timed, at most kFftPlanTimeLimitSeconds per plan).
//   Timing can pick different algorithms in different runs, and different algorithms round
//   differently, so a measured plan is only made deterministic by WISDOM: with a wisdom file
//   (set_fft_wisdom_file) the first run's choice is recorded and every later run rebuilds exactly
//   that plan. `pinmask` measures only when a wisdom file is in use (PINMASK_WISDOM=off selects
//   kEstimate), see cli/options/fft_setup.
// - Threads: transforms of at least kFftThreadMinPixels use fft_threads() FFTW threads.
#pragma once

#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

using ComplexPlaneF =
    Eigen::Array<std::complex<float>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

enum class FftPlanner { kEstimate, kMeasure };

// Transforms with at least this many real samples (512 x 512) are planned with fft_threads().
inline constexpr long long kFftThreadMinPixels = 512LL * 512LL;
// Upper bound of FFTW's measuring for one plan (fftw_set_timelimit).
inline constexpr double kFftPlanTimeLimitSeconds = 5.0;

// Process-wide planner mode and thread count (>= 1; InvalidInput otherwise) for plans made
// afterwards; plans already cached keep theirs.
void set_fft_planner(FftPlanner planner);
FftPlanner fft_planner();
void set_fft_threads(int threads);
int fft_threads();
// FFTW threads a plan of rows x cols gets: fft_threads() from kFftThreadMinPixels up, else 1.
int fft_threads_for(int rows, int cols);

// Planning done by this process so far (plans made, plans rebuilt from wisdom, seconds spent).
struct FftPlanStats {
    int plans = 0;
    int plans_from_wisdom = 0;  // made while an identical problem was already in the wisdom
    double planning_seconds = 0.0;
};
FftPlanStats fft_plan_stats();

// Wisdom: a pinmask wisdom file holds a header (format, version, FFTW version, CPU model) and the
// double and single precision FFTW wisdom. set_fft_wisdom_file(path) imports it (when present)
// and records the path; every plan measured afterwards is merged into it at once (written to a
// temporary and renamed). A file that is corrupt, of another format, another FFTW version or
// another CPU is ignored (not trusted) and replaced at the next export. Problems never throw:
// they are returned as warnings (the libraries never print; the CLI does).
// An empty path disables wisdom. Returns the warnings of the import (empty when all is well).
std::vector<std::string> set_fft_wisdom_file(const std::string& path);
std::string fft_wisdom_file();
// Warnings recorded since the last call (failed exports), cleared by the call.
std::vector<std::string> take_fft_warnings();
// The wisdom text this process would write (header + FFTW wisdom), and a check of such text:
// empty when it can be trusted, else the reason it is refused.
std::string fft_wisdom_text();
std::string fft_wisdom_problem(const std::string& text);

// Real 2-D transform pair of one size (rows x cols, both >= 1).
class Fft2 {
  public:
    Fft2(int rows, int cols);

    int rows() const { return rows_; }
    int cols() const { return cols_; }
    int half_cols() const { return cols_ / 2 + 1; }

    // Half spectrum of x (rows x half_cols). x must be rows x cols.
    ComplexPlane forward(const Plane& x) const;
    void forward(const Plane& x, ComplexPlane& out) const;

    // Real plane from a half spectrum, including the 1/(rows cols) factor.
    Plane inverse(const ComplexPlane& spectrum) const;
    // Allocation-free form: `scratch` is resized on first use and reused (c2r destroys input).
    void inverse(const ComplexPlane& spectrum, Plane& out, ComplexPlane& scratch) const;
    // In-place form without the copy: destroys `spectrum`; no 1/N factor (the caller applies it,
    // e.g. folded into a filter). out must not alias spectrum.
    void inverse_unscaled_destroy(ComplexPlane& spectrum, Plane& out) const;

  private:
    int rows_, cols_;
    void* r2c_;  // fftw_plan, owned by the process-wide cache
    void* c2r_;
};

// Single-precision real 2-D transform pair (fftwf), same conventions as Fft2.
class Fft2f {
  public:
    Fft2f(int rows, int cols);
    int rows() const { return rows_; }
    int cols() const { return cols_; }
    int half_cols() const { return cols_ / 2 + 1; }
    void forward(const PlaneF& x, ComplexPlaneF& out) const;
    // Includes the 1/(rows cols) factor; `scratch` reused (c2r destroys its input).
    void inverse(const ComplexPlaneF& spectrum, PlaneF& out, ComplexPlaneF& scratch) const;
    // Destroys `spectrum`; no 1/N factor.
    void inverse_unscaled_destroy(ComplexPlaneF& spectrum, PlaneF& out) const;

  private:
    int rows_, cols_;
    void* r2c_;  // fftwf_plan
    void* c2r_;
};

// Complex 2-D transform pair of one size (full spectrum, same conventions).
class FftC2 {
  public:
    FftC2(int rows, int cols);
    int rows() const { return rows_; }
    int cols() const { return cols_; }
    ComplexPlane forward(const ComplexPlane& x) const;
    ComplexPlane inverse(const ComplexPlane& x) const;  // includes 1/(rows cols)

  private:
    int rows_, cols_;
    void* fwd_;
    void* bwd_;
};

// Full rows x cols spectrum from a half spectrum of a real plane (Hermitian symmetry).
ComplexPlane expand_half_spectrum(const ComplexPlane& half, int cols);

}  // namespace pinmask
