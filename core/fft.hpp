// FFT wrapper over FFTW3 (double precision). Conventions, written down once for the project:
//
//   forward  X[k, l] = sum_{r, c} x[r, c] exp(-2 pi i (k r / R + l c / C))      (unnormalised)
//   inverse  x[r, c] = 1/(R C) sum_{k, l} X[k, l] exp(+2 pi i (k r / R + l c / C))
//
// The 1/(R C) factor is applied in inverse() and nowhere else, so forward followed by inverse is
// the identity. Layout is row-major (Eigen RowMajor == FFTW's C order). Real transforms use the
// half spectrum: an R x C real plane maps to R x (C/2 + 1) complex coefficients, the columns
// l = 0 .. C/2; the rest follow from Hermitian symmetry X[k, l] = conj(X[-k, -l]).
//
// Plans are made once per (kind, size) with FFTW_ESTIMATE (deterministic: no timing-dependent
// choices), cached for the life of the process, and created under one mutex, so Fft2 objects may
// be constructed and used from any thread. Executing a plan is thread-safe. Plans are SIMD-
// aligned; Eigen buffers are 64-byte aligned project-wide (CMakeLists.txt), and other buffers
// are copied through aligned temporaries, so results never depend on buffer addresses.
#pragma once

#include "core/image.hpp"

namespace pinmask {

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

  private:
    int rows_, cols_;
    void* r2c_;  // fftw_plan, owned by the process-wide cache
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
