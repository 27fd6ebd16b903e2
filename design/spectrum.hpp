// The light's spectrum as the kernels see it: the camera's band (design/camera: centre
// wavelength_m, full width at half maximum bandwidth_m) as weighted wavelength samples, the list
// a polychromatic kernel sums (design/kernel.hpp, KernelSpec::wavelengths).
//
// Rule: a Gaussian spectrum of that FWHM (sigma = B / (2 sqrt(2 ln 2))), sampled at
// kBandSamples = 7 wavelengths lambda + k B / 2, k = -3..3 (+-1.5 FWHM = +-3.53 sigma, where the
// Gaussian has fallen to 0.2 % of its peak), weights exp(-(k B / 2)^2 / (2 sigma^2)) normalised
// to sum 1. An LED's emission is close to a Gaussian of its datasheet FWHM; the kernel changes
// smoothly with lambda (its scale goes as lambda), so 7 samples spaced 1.18 sigma apart
// integrate it well (docs/commands.md gives the measured difference from 61 samples).
// bandwidth_m = 0 is the single design wavelength with weight 1.
#pragma once

#include <utility>
#include <vector>

#include "design/camera.hpp"

namespace pinmask {

inline constexpr int kBandSamples = 7;

// (wavelength_m, weight) pairs, weights summing to 1, shortest wavelength first. The camera is
// validated first (InvalidInput naming bandwidth_m for a band that is not physical).
std::vector<std::pair<double, double>> band_wavelengths(const Camera& camera);

}  // namespace pinmask
