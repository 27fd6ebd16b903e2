// The analytic Wiener model as `pinmask search` builds it, shared with `pinmask compare` so both
// report the same figure: the single-pinhole kernel's full m x m spectrum (m = n * pixels per
// cell, design/psf.hpp kernel_spectrum expanded by core/fft.hpp), a natural-scene prior of
// `prior_scenes` 1/f textures at m x m (optimize/scene_prior.hpp, seeds 0 ..), and Gaussian
// noise at a capture SNR in dB (optimize/noise_model.hpp).
#pragma once

#include <string>

#include "design/kernel.hpp"
#include "optimize/analytic_error.hpp"
#include "optimize/simulated_metrics.hpp"

namespace pinmask::cli {

// Natural scenes averaged for the prior unless a command says otherwise (search --prior-scenes).
inline constexpr int kDefaultPriorScenes = 16;

// The model for a kernel on an n x n grid of pixels_per_cell pixels per cell.
AnalyticWienerModel analytic_wiener_model(const Kernel& kernel, int n, int pixels_per_cell,
                                          double snr_db, int prior_scenes = kDefaultPriorScenes);

// "optimal" (per-frequency Wiener filter) or "nsr:VALUE" (deconvwnr's fixed NSR, > 0);
// InvalidInput naming --filter otherwise.
WienerFilterSpec parse_wiener_filter(const std::string& text);

// A simulated decoder's weight (Wiener NSR, TV lambda): "tuned" or a number > 0; InvalidInput
// naming `flag` otherwise.
WeightChoice parse_weight_choice(const std::string& text, const std::string& flag);

}  // namespace pinmask::cli
