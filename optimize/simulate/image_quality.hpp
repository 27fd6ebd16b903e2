// Image quality against a reference, for images whose values live in [0, 1] (peak L = 1).
//
// MSE  = mean((x - ref)^2) over all pixels (and channels).
// PSNR = 10 log10(1 / MSE) dB (+inf for MSE = 0).
// SSIM (Wang, Bovik, Sheikh, Simoncelli, IEEE TIP 13(4), 2004) with the paper's parameters:
// an 11 x 11 Gaussian window of standard deviation 1.5 pixels (normalised to sum 1),
// K1 = 0.01, K2 = 0.03, L = 1, C1 = (K1 L)^2, C2 = (K2 L)^2, and for every window position
//     SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 +
//     C2))
// with weighted means, variances and covariance (weights sum to 1, no n/(n-1) correction).
// Border handling: only windows lying wholly inside the image are used ("valid" filtering, as
// in the paper's reference code), so the map is (rows - 10) x (cols - 10) and the mean SSIM is
// its average; images smaller than 11 x 11 are rejected. Multi-channel: mean over channels.
#pragma once

#include "core/image/image.hpp"

namespace pinmask {

inline constexpr int kSsimWindow = 11;     // window side, pixels
inline constexpr double kSsimSigma = 1.5;  // Gaussian window standard deviation, pixels
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;

// Mean squared error. Throws InvalidInput when the sizes differ or a plane is empty.
double mse(const Plane& x, const Plane& ref);

// 10 log10(1 / mse): +inf when mse == 0. Throws InvalidInput for mse < 0 or NaN.
double psnr_from_mse(double mse);

// PSNR of x against ref, peak 1.
double psnr_db(const Plane& x, const Plane& ref);

// The (rows - 10) x (cols - 10) SSIM map. Throws InvalidInput when the sizes differ or either
// dimension is below 11.
Plane ssim_map(const Plane& x, const Plane& ref);

// Mean of ssim_map.
double ssim(const Plane& x, const Plane& ref);

// Multi-channel forms: same channel count and size required; MSE over all samples, SSIM as the
// mean of the per-channel SSIMs.
double mse(const Image& x, const Image& ref);
double psnr_db(const Image& x, const Image& ref);
double ssim(const Image& x, const Image& ref);

}  // namespace pinmask
