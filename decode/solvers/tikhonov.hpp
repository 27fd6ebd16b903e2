// Tikhonov deconvolution in closed form: x = argmin ||A x - p||_2^2 + lambda ||L x||_2^2 with
// L = I (identity) or L = grad (periodic differences, decode/solvers/gradient.hpp).
//
// For the cyclic model A is diagonal in Fourier space and the normal equations
// (A^T A + lambda L^T L) x = A^T p are solved exactly by the spectral filter
//   G = conj(H) / (|H|^2 + lambda |L|^2),   |L|^2 = 1 or 4 sin^2(pi k / R) + 4 sin^2(pi l / C),
// with G = 0 where the denominator is 0 (H = 0 and, for grad, the zero frequency; lambda = 0
// then gives the pseudo-inverse). No floor is applied (unlike deconvwnr). For the linear model
// the same filter is applied on the padded grid to the zero-padded capture: an approximation
// that ignores the crop (as for Wiener).
#pragma once

#include "core/image/image.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/wiener.hpp"

namespace pinmask {

// The Tikhonov filter for a rows x cols working grid; lambda finite and >= 0 (field "lambda").
WienerFilter make_tikhonov_filter(const Plane& psf, int rows, int cols, double lambda,
                                  TikhonovRegulariser regulariser);

// The same from H = psf2otf(psf, rows, cols) already computed (half spectrum, field "otf").
WienerFilter make_tikhonov_filter_from_otf(const ComplexPlane& otf, int rows, int cols,
                                           double lambda, TikhonovRegulariser regulariser);
// |L|^2 on the half spectrum: 1 (identity) or 4 sin^2(pi k / R) + 4 sin^2(pi l / C) (gradient).
Plane tikhonov_symbol(int rows, int cols, TikhonovRegulariser regulariser);

// lambda ||L x||_2^2 for the given regulariser.
double tikhonov_penalty(const Plane& x, double lambda, TikhonovRegulariser regulariser);

}  // namespace pinmask
