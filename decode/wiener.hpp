// Wiener deconvolution with MATLAB deconvwnr semantics, as a reusable precomputed filter.
//
// Notation: p the capture (R x C), H = psf2otf(a, R, C) (decode/psf2otf.hpp), NSR the
// noise-to-signal power ratio, scalar or one value per frequency. The estimate is
//   x = real(ifft2(G .* fft2(p))),   G = conj(H) / max(|H|^2 + NSR, floor).
// deconvwnr floors the denominator at sqrt(eps) = 1.49e-8 (kDeconvwnrDenominatorFloor, the
// default here): NSR = 0 is then the ideal inverse filter wherever |H|^2 >= 1.49e-8, a
// frequency with H = 0 gives 0, never NaN or Inf. A floor of 0 gives the unfloored formula,
// with 0 where |H|^2 + NSR = 0 (which, NSR being >= 0, only happens where H = 0 too).
// A per-frequency NSR is a full R x C array indexed like fft2 output (row k, column l is the
// frequency (k / R, l / C)), as in deconvwnr. The real part is taken exactly: the half spectrum
// keeps the Hermitian part of G, (G(k) + conj(G(-k))) / 2, which equals G for a scalar or
// symmetric NSR.
#pragma once

#include "core/fft.hpp"
#include "core/image.hpp"

namespace pinmask {

// sqrt(DBL_EPSILON): deconvwnr's floor of the Wiener denominator |H|^2 + NSR.
inline constexpr double kDeconvwnrDenominatorFloor = 1.4901161193847656e-08;

// A precomputed spectral filter x = real(ifft2(G .* fft2(p))) for one (PSF, NSR, size): built
// once, applied to any number of channels and frames. apply() is const and thread-safe when each
// thread passes its own Workspace.
class WienerFilter {
  public:
    // Reusable buffers of apply(); sized on first use.
    struct Workspace {
        ComplexPlane spectrum;
        ComplexPlane scratch;
    };
    // Buffers of apply_single().
    struct WorkspaceF {
        PlaneF in, out;
        ComplexPlaneF spectrum;
    };

    // Scalar NSR >= 0 (field "nsr"), capture size rows x cols, denominator floor >= 0.
    WienerFilter(const Plane& psf, int rows, int cols, double nsr,
                 double denominator_floor = kDeconvwnrDenominatorFloor);
    // Per-frequency NSR: a rows x cols array of finite values >= 0 (field "nsr_per_frequency").
    WienerFilter(const Plane& psf, int rows, int cols, const Plane& nsr_per_frequency,
                 double denominator_floor = kDeconvwnrDenominatorFloor);
    // Any precomputed Hermitian filter given as its half spectrum rows x (cols / 2 + 1).
    static WienerFilter from_half_spectrum(ComplexPlane g_half, int rows, int cols);

    int rows() const { return rows_; }
    int cols() const { return cols_; }

    // x = real(ifft2(G .* fft2(capture))); capture must be rows x cols.
    Plane apply(const Plane& capture) const;
    // Allocation-free form (after the first call with a given workspace).
    void apply(const Plane& capture, Plane& out, Workspace& ws) const;
    // The same filter in single precision (FFTW float; the filter rounded to float once): the
    // result differs from apply() by float rounding, a relative l2 error of a few 1e-7 times
    // log2(N) for a filter of modest gain (tests/decode/test_wiener.cpp states the bound).
    void apply_single(const Plane& capture, Plane& out, WorkspaceF& ws) const;

    // max_k |G(k)|: the l2 gain of the filter (an error e in the capture moves x by at most
    // gain() * ||e||_2 in the l2 norm, by Parseval).
    double gain() const;
    // The filter's half spectrum, rows x (cols / 2 + 1).
    const ComplexPlane& half_spectrum() const { return g_; }

  private:
    WienerFilter(int rows, int cols, ComplexPlane g);
    int rows_, cols_;
    void finish();  // fills the scaled copies below from g_
    Fft2 fft_;
    ComplexPlane g_;
    ComplexPlane g_scaled_;     // g_ / (rows cols): the inverse FFT's 1/N folded in
    ComplexPlaneF g_scaled_f_;  // the same in float
};

}  // namespace pinmask
