// Fabrication errors of a pinhole mask (`--robust size=5um,jitter=2um,
// missing=0.01`) and the per-axis statistics of position jitter on the pixel grid.
//
// The error model, once for every robust figure (optimize/metrics/robust_wiener, robust_sample):
//   size    a systematic side bias b: every pinhole of one fabricated mask has side d + b or
//           d - b (over- or under-etched), each sign with probability 1/2. The kernel becomes
//           design/psf/kernel's kernel of a pinhole of that side (normalised to sum 1: the changed
//           brightness is an exposure the user sets, not a decoding error).
//   jitter  every pinhole centre moves independently by (dr, dc) on the mask, each axis normal
//           with standard deviation sigma (metres on the mask; sigma ppc / d pixels on the
//           sensor, one cell being d on the mask and ppc pixels on the sensor). The spot moves by
//           area resampling, as design/psf/psf_exact does: a fractional shift f spreads each kernel
//           pixel over the two pixels it overlaps with weights 1 - f and f.
//   missing every pinhole is independently closed (not opened by the fabrication) with
//           probability q; the capture is scaled by 1 / ((1 - q) K) instead of 1 / K, so the
//           expected fabricated PSF keeps sum 1 (again: brightness is exposure, not error).
// The decoder keeps the nominal (design) PSF: the mask is used uncalibrated.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace pinmask {

struct FabricationErrors {
    double size_bias_m = 0.0;  // b >= 0: sides d + b and d - b, each half of the fabrications
    double jitter_m = 0.0;     // sigma >= 0 per axis, on the mask
    double missing = 0.0;      // q in [0, 1)

    bool any() const { return size_bias_m > 0.0 || jitter_m > 0.0 || missing > 0.0; }

    // InvalidInput naming "`robust` <key>", the value and the rule: finite and >= 0 everywhere;
    // missing < 1 (a mask without pinholes images nothing); with the pinhole side d > 0 known
    // (pinhole_m > 0): size <= (1 - 1e-6) d (a side d - b <= 0 has no hole) and jitter <= d.
    void validate(double pinhole_m = 0.0) const;

    // "size +-5 um, jitter 2 um, missing 0.01" ("none" without errors).
    std::string description() const;
};

// "size=5um,jitter=2um,missing=0.01": any subset of the three keys, each at most once; lengths
// with the units of the other length flags (core/units/units: m, mm, um, nm; plain numbers are
// metres), missing a plain probability. InvalidInput naming `robust` and the key for an unknown or
// repeated key, an item without '=', a bad number or a value out of range.
FabricationErrors parse_fabrication_errors(const std::string& text);

// Statistics of the area-resampled shift of a spot by delta ~ N(0, sigma^2) pixels along one
// axis, at the m DFT frequencies theta_k = 2 pi k / m of that axis. With delta = s + f (s whole,
// 0 <= f < 1) the shift's transfer function is t(delta, theta) = e^{-i theta s} (1 - f +
// f e^{-i theta}); mean[k] = E t, power[k] = E |t|^2 = E[(1 - f)^2 + f^2 + 2 f (1 - f) cos theta].
// Computed by Gauss-Legendre quadrature on panels split at whole pixels, over +-9 sigma (the
// weights renormalised to sum 1). sigma = 0 gives mean = power = 1. sigma_px finite, >= 0.
struct JitterTransfer {
    std::vector<std::complex<double>> mean;
    std::vector<double> power;
};
JitterTransfer jitter_transfer(double sigma_px, int m);

}  // namespace pinmask
