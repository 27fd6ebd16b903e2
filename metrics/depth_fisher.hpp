// Depth discriminability of a mask: the Fisher information of the object distance carried by the
// capture of a point source on the axis, and its Cramer-Rao bound on the distance.
//   Parameter t = 1/u (the pattern's scale is linear in it, Eq. (3)). Mean capture
//   mu(t) = photons h_t, h_t the exact-geometry PSF (design/psf_exact) over a
//   rows x cols window centred on the axis (each basic-pattern pinhole weighs 1/K, so `photons`
//   is the electrons of one period's light). Noise: Poisson photon noise plus Gaussian read noise,
//   variance mu + read_noise^2 per pixel (the Gaussian approximation of the photon model).
//   I(t) = sum_pixels (d mu / dt)^2 / (mu + read_noise^2), the derivative by a central difference
//   in t with step one twentieth of the one-pixel step w / (f N_t d) (the area-resampled PSF is
//   piecewise linear in the spot positions, so the difference is exact up to the kinks it
//   crosses). Bound: sigma_t >= 1 / sqrt(I), sigma_u = u^2 sigma_t.
// Pixels with zero variance (no light, no read noise) carry no term.
#pragma once

#include "design/mask.hpp"

namespace pinmask {

struct DepthFisherOptions {
    double photons = 20000;   // electrons of the point source over one period (> 0)
    double read_noise_e = 0;  // rms electrons (>= 0)
    int rows = 0, cols = 0;   // window; 0 = the camera's sensor
    void validate() const;    // InvalidInput naming the field
};

struct DepthFisher {
    double object_distance_m = 0;
    double fisher_inverse_m2 = 0;        // I(t), t = 1/u in 1/m: units m^2
    double crb_inverse_per_m = 0;        // 1 / sqrt(I): the bound on sigma(1/u), 1/m
    double crb_distance_m = 0;           // u^2 / sqrt(I): the bound on sigma(u), m
    double one_pixel_inverse_per_m = 0;  // w / (f N_t d): one pixel of pattern change in 1/u
};

// u finite, > f' when there is a lens. Throws InvalidInput naming the field.
DepthFisher depth_fisher(const Mask& mask, double object_distance_m,
                         const DepthFisherOptions& options);

}  // namespace pinmask
