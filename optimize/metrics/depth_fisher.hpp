// Depth discriminability of a mask: the Fisher information of the object distance carried by the
// capture of a point source on the axis, and its Cramer-Rao bound on the distance.
//   Parameter t = 1/u (the pattern's scale is linear in it, Eq. (3)). Mean capture
//   mu(t) = photons h_t, h_t the exact-geometry PSF (design/psf/psf_exact) over a
//   rows x cols window centred on the axis (each basic-pattern pinhole weighs 1/K, so `photons`
//   is the electrons of one period's light). Noise: Poisson photon noise plus Gaussian read noise,
//   variance mu + read_noise^2 per pixel (the Gaussian approximation of the photon model).
//   I(t) = sum_pixels (d mu / dt)^2 / (mu + read_noise^2), the derivative by a central difference
//   in t with step one twentieth of the one-pixel step w / (f N_t d) (the area-resampled PSF is
//   piecewise linear in the spot positions, so the difference is exact up to the kinks it
//   crosses). Bound: sigma_t >= 1 / sqrt(I), sigma_u = u^2 sigma_t.
// Pixels with zero variance (no light, no read noise) carry no term.
#pragma once

#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "optimize/simulate/noise_model.hpp"

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

// The noise-free part of the bound at one u, shared by several noise levels: the exact PSF h at
// u over the window and its derivative dh/dt by the central difference above (per unit photon).
struct DepthSlope {
    double object_distance_m = 0;
    double one_pixel_inverse_per_m = 0;
    Plane psf, slope;
};
DepthSlope depth_slope(const Mask& mask, double object_distance_m, int rows, int cols);

// The bound from a slope under photons and read noise (options.rows/cols are not used).
DepthFisher depth_fisher(const DepthSlope& slope, const DepthFisherOptions& options);

// The photon model's point source for the bound: a scene pixel of value 1 sends
// photons_per_pinhole * K electrons through one period (the capture of a scene of value 1
// everywhere has photons_per_pinhole * K electrons per pixel, optimize/simulate/noise_model.hpp),
// so photons = photons_per_pinhole * K; the per-pixel variance adds read_noise^2, the dark current
// and the ADC step q^2 / 12 as one read noise. The film's leak is left out (for one scene pixel
// it is photons_per_pinhole * T * (n^2 - K) / m^2 electrons per pixel, below 1e-3 e at
// the default opaque film). InvalidInput naming `photons` for a model that is not the photon
// model.
DepthFisherOptions depth_fisher_noise(const NoiseModel& model, int open_cells);

// ---- The depth figure over a range of distances (score's and compare's `depth` group) ----
// Samples u_k equally spaced in 1/u from from_m to to_m (both ends included; one sample when
// they are equal). 0 for both: the mask's working distance u_w, from u_w / 2 to 2 u_w (an
// infinite u_w has no default: InvalidInput naming `depth_from_m`).
inline constexpr int kDepthSamples = 3;
struct DepthRange {
    double from_m = 0, to_m = 0;  // 0 and 0: around the working distance
    int samples = kDepthSamples;  // 1 .. 64
    void validate() const;        // InvalidInput naming depth_from_m / depth_to_m / samples
};

// The range's ends for a mask (the defaults resolved; each end checked against the camera).
std::vector<double> depth_samples(const Mask& mask, const DepthRange& range);

// The worst (largest) figures over the samples for one noise level.
struct DepthFigures {
    double from_m = 0, to_m = 0;
    double crb_rel = 0;           // max_k sigma_u(u_k) / u_k (Cramer-Rao, relative)
    double axial_fwhm_m = 0;      // max_k 2.355 sigma_u(u_k): the axial resolution, metres
    double worst_distance_m = 0;  // the u_k of crb_rel
};
DepthFigures depth_figures(const std::vector<DepthSlope>& slopes,
                           const DepthFisherOptions& options);

}  // namespace pinmask
