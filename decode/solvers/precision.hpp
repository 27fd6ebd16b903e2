// The types of one floating-point precision for the solvers of decode/ (and the forward
// simulation of optimize/simulate/): the real plane, its half spectrum and the FFT pair of
// core/fft/fft (Fft2 for double, Fft2f for float32), so a solver written once as a template over T
// runs in either precision with the same FFT conventions.
//
// Float range: a float32 run is safe when every quantity it holds stays far
// from FLT_MAX (3.4e38) and the FFTs' sums (at most N times the largest input) do too. The
// solvers work on normalised problems (capture / max|p|, see decode/capture/decoder.hpp), so the
// only inputs that can leave the range are PSFs whose values cancel: |H| <= sum|a| while the
// decoder divides by sum(a). fits_single_precision() says whether a value stays below
// kSingleSafeMagnitude, the bound used by every such check (1e30: 3.4e8 of headroom for the FFT
// sums of a 1e8-pixel plane).
#pragma once

#include <cmath>
#include <string>

#include "core/fft/fft.hpp"
#include "core/image/image.hpp"

namespace pinmask {

inline constexpr double kSingleSafeMagnitude = 1e30;

// --precision auto: float32 from 256 x 256 pixels (decoded window, simulated convolution grid).
// From here on float32 pays (bench decode) and its error stays below the bounds of
// tests/decode/test_precision.cpp.
inline constexpr long long kSinglePrecisionMinPixels = 256LL * 256LL;

template <class T>
struct PrecisionTypes;
template <>
struct PrecisionTypes<double> {
    using Plane = pinmask::Plane;
    using Spectrum = ComplexPlane;
    using Fft = Fft2;
};
template <>
struct PrecisionTypes<float> {
    using Plane = PlaneF;
    using Spectrum = ComplexPlaneF;
    using Fft = Fft2f;
};

// True when |v| <= kSingleSafeMagnitude (false for NaN).
inline bool fits_single_precision(double v) { return std::fabs(v) <= kSingleSafeMagnitude; }

// Empty when a decode with this PSF can run in float32, else the reason (for --explain and the
// refusal of --precision single): the PSF's gain sum|a| / |sum a| (how far |H| can exceed the
// decoder's unit-sum normalisation) must fit kSingleSafeMagnitude.
std::string single_precision_problem(const Plane& psf);

}  // namespace pinmask
