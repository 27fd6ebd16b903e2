// The light's spectrum as the kernels see it: the camera's band (design/optics/camera: centre
// wavelength_m, full width at half maximum bandwidth_m) as weighted wavelength samples, the list
// a polychromatic kernel sums (design/psf/kernel.hpp, KernelSpec::wavelengths).
//
// Rule: a Gaussian spectrum of that FWHM (sigma = B / (2 sqrt(2 ln 2))), sampled at
// kBandSamples = 13 wavelengths lambda + k B / 4, k = -6..6 (+-1.5 FWHM = +-3.53 sigma, where the
// Gaussian has fallen to 0.2 % of its peak), weights exp(-(k B / 4)^2 / (2 sigma^2)) normalised
// to sum 1. An LED's emission is close to a Gaussian of its datasheet FWHM; the kernel's fringes
// move with lambda, and samples 0.59 sigma apart follow them: on the paper's camera with a 60 nm
// band the PSF is 3.8e-5 (L1) from a 241-sample reference, where 7 samples 1.18 sigma apart
// leave 2.0e-3 (docs/commands.md, with the command).
// bandwidth_m = 0 is the single design wavelength with weight 1.
#pragma once

#include <utility>
#include <vector>

#include "design/optics/camera.hpp"

namespace pinmask {

inline constexpr int kBandSamples = 13;

// (wavelength_m, weight) pairs, weights summing to 1, shortest wavelength first. The camera is
// validated first (InvalidInput naming bandwidth_m for a band that is not physical).
std::vector<std::pair<double, double>> band_wavelengths(const Camera& camera);

}  // namespace pinmask
