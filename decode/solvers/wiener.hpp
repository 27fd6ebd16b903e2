// Wiener deconvolution with MATLAB deconvwnr semantics, as a reusable precomputed filter.
//
// Notation: p the capture (R x C), H = psf2otf(a, R, C) (decode/solvers/psf2otf.hpp), NSR the
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

#include <optional>

#include "core/fft/fft.hpp"
#include "core/image/image.hpp"

namespace pinmask {

// sqrt(DBL_EPSILON): deconvwnr's floor of the Wiener denominator |H|^2 + NSR.
inline constexpr double kDeconvwnrDenominatorFloor = 1.4901161193847656e-08;

// Sums over the full spectrum gathered while a filter is applied, by Parseval from the half
// spectrum, with no transform beyond the filter's own pair. X = F[x] the estimate's spectrum,
// P = F[capture], N = rows cols:
//   residual2 = (1/N) sum_full |H X - P|^2 = ||h (*) x - capture||_2^2 (circular convolution)
//   penalty   = (1/N) sum_half weight |X|^2
// `weight` is a half spectrum that already counts each coefficient's Hermitian partner (see
// half_spectrum_multiplicity and fold_full_spectrum_weight), e.g. nsr * multiplicity gives
// nsr ||x||_2^2; `uniform_weight` w stands for the weight w * multiplicity without a plane. Set
// otf and/or a weight to ask for the sum; the other stays 0.
struct SpectralSums {
    const ComplexPlane* otf = nullptr;
    const Plane* weight = nullptr;
    std::optional<double> uniform_weight;  // excludes `weight`
    double residual2 = 0.0;
    double penalty = 0.0;
};

// 1 for the half-spectrum columns that are their own Hermitian partner's column (l = 0 and, for
// even cols, l = cols / 2), else 2: sum_full f = sum_half multiplicity f for a symmetric f.
Plane half_spectrum_multiplicity(int rows, int cols);
// A full rows x cols weight w folded onto the half spectrum: w(k, l) + w(-k, -l) where the
// partner lies outside the half spectrum, else w(k, l), so sum_full w |X|^2 = sum_half fold |X|^2
// for the spectrum X of a real plane (|X(-k)| = |X(k)|).
Plane fold_full_spectrum_weight(const Plane& full);

// A precomputed spectral filter x = real(ifft2(G .* fft2(p))) for one (PSF, NSR, size): built
// once, applied to any number of channels and frames. apply() is const and thread-safe when each
// thread passes its own Workspace.
class WienerFilter {
  public:
    // Reusable buffers of apply(); sized on first use.
    struct Workspace {
        ComplexPlane spectrum;
        ComplexPlane scratch;
        Plane scaled;  // capture / scale, when scale != 1
    };
    // Buffers of apply_single().
    struct WorkspaceF {
        PlaneF in, out;
        ComplexPlaneF spectrum;
        ComplexPlaneF filter;  // the float filter, for sizes without a stored copy
    };

    // Scalar NSR >= 0 (field "nsr"), capture size rows x cols, denominator floor >= 0.
    WienerFilter(const Plane& psf, int rows, int cols, double nsr,
                 double denominator_floor = kDeconvwnrDenominatorFloor);
    // Per-frequency NSR: a rows x cols array of finite values >= 0 (field "nsr_per_frequency").
    WienerFilter(const Plane& psf, int rows, int cols, const Plane& nsr_per_frequency,
                 double denominator_floor = kDeconvwnrDenominatorFloor);
    // Any precomputed Hermitian filter given as its half spectrum rows x (cols / 2 + 1).
    static WienerFilter from_half_spectrum(ComplexPlane g_half, int rows, int cols);
    // The same filters from the transfer function H = psf2otf(psf, rows, cols) already computed
    // (half spectrum rows x (cols / 2 + 1), field "otf"), so a caller holding H (the decoder's
    // convolution operator) does not transform the PSF a second time.
    static WienerFilter from_otf(const ComplexPlane& otf, int rows, int cols, double nsr,
                                 double denominator_floor = kDeconvwnrDenominatorFloor);
    static WienerFilter from_otf(const ComplexPlane& otf, int rows, int cols,
                                 const Plane& nsr_per_frequency,
                                 double denominator_floor = kDeconvwnrDenominatorFloor);

    int rows() const { return rows_; }
    int cols() const { return cols_; }

    // x = real(ifft2(G .* fft2(capture))); capture must be rows x cols.
    Plane apply(const Plane& capture) const;
    // Allocation-free form (after the first call with a given workspace).
    // With `sums`, its requested sums are gathered in the pass that applies the filter.
    // `scale` (a power of two, so exact): the filter sees capture / scale and out is scale times
    // its result, i.e. the same x, computed in a range that cannot overflow; the sums are those
    // of the scaled problem (times scale^2 for the capture's units).
    void apply(const Plane& capture, Plane& out, Workspace& ws, SpectralSums* sums = nullptr,
               double scale = 1.0) const;
    // The same filter in single precision (FFTW float; the filter rounded to float once): the
    // result differs from apply() by float rounding, a relative l2 error of a few 1e-7 times
    // log2(N) for a filter of modest gain (tests/decode/test_wiener.cpp states the bound).
    // `sums` as in apply(), from the float spectrum that is inverse-transformed (summed in double).
    // `scale` as in apply(), folded into the conversions to and from float (no extra pass).
    void apply_single(const Plane& capture, Plane& out, WorkspaceF& ws,
                      SpectralSums* sums = nullptr, double scale = 1.0) const;

    // max_k |G(k)|: the l2 gain of the filter (an error e in the capture moves x by at most
    // gain() * ||e||_2 in the l2 norm, by Parseval).
    double gain() const;
    // The filter's half spectrum, rows x (cols / 2 + 1).
    const ComplexPlane& half_spectrum() const { return g_; }

  private:
    WienerFilter(int rows, int cols, ComplexPlane g);
    int rows_, cols_;
    void finish();  // fills the scaled copies below from g_
    void check_capture(const Plane& capture) const;
    Fft2 fft_;
    ComplexPlane g_;
    ComplexPlane g_scaled_;     // g_ / (rows cols): the inverse FFT's 1/N folded in
    ComplexPlaneF g_scaled_f_;  // the same in float (from kSinglePrecisionMinPixels up)
};

}  // namespace pinmask
