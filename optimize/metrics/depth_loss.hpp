// Depth analysis of a mask (pinmask depth): for each object distance u, the figures of
// design/optics/working_distance (pitch, period, LSI mismatch against the mask's whole pixels per
// cell) and the PSNR lost when the capture the camera records at u (exact geometry,
// design/psf/psf_exact: scene (*) exact PSF, linear convolution, optimize/simulate/simulate
// linear_capture) is decoded with the mask's integer cyclic PSF, for Wiener and TV-L2
// (decode/capture/decoder decode_plane).
//   reference PSNR: the cyclic capture scene (*) A (the decoder's own model) with the same noise
//                   draw, decoded the same way;
//   exact PSNR:     on an even window holding the tiled mask's spots and the scene (the axis on a
//                   pixel corner), the centred m x m crop of the exact capture (the decoder's
//                   default window), decoded; the scene then appears cyclically shifted (its centre
//                   sits on the optical axis, not on the crop's centre), so both decodes are
//                   compared with the scene after the integer cyclic shift that maximises their
//                   correlation;
//   loss = reference PSNR - exact PSNR, dB, averaged over the scenes.
// Noise: any model of optimize/simulate/noise_model (Gaussian at an SNR from each capture's own
// mean square, the photon model with its sensor stages, or none), one seeded generator per scene
// shared by both captures (K = the pattern's pinholes, n^2 its cells, for the photon model).
// Wiener NSR: a given value, or tuned as score tunes it (optimize/metrics/simulated_metrics: the
// NSR minimising the mean MSE of the cyclic captures of the same scenes under the same noise
// model), once per run; both decodes use it. Cost: the reference decodes do not depend on u and run
// once. Only the centred m x m crop of the exact capture is decoded, and it depends only on the
// exact PSF within m pixels of the axis, so the PSF is computed on a 2m x 2m window and the crop by
// one cyclic convolution of side 2m (exactly the crop of the full linear capture: no wrapped term
// reaches it).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

struct DepthOptions {
    std::vector<std::string> scenes{"letter-R", "natural"};  // optimize/simulate/scenes names
    NoiseModel noise;                                        // Gaussian 30 dB by default
    WeightChoice wiener_nsr{true, 0.01};                     // tuned unless a value is given
    double tv_lambda = 1e-3;                                 // as pinmask score's default
    int tv_iterations = 100;                                 // >= 1
    bool with_tv = true;
    std::uint64_t seed = 1;
    int threads = 1;  // worker threads over (distance, scene) pairs, 1..256; figures do not change
    // Called (from a worker thread, one call at a time) after the set-up (done 0) and after each
    // distance (done = distances finished).
    std::function<void(std::size_t done, std::size_t total)> progress;
    // Throws InvalidInput naming the field, value and rule.
    void validate() const;
};

struct DepthRecord {
    double object_distance_m = 0;
    double pixels_per_cell = 0;  // pitch at u, px
    double period_px = 0;        // n pitch
    double lsi_mismatch_px = 0;  // n |pitch - mask's pixels per cell|
    double wiener_psnr_loss_db = 0;
    double tv_psnr_loss_db = std::numeric_limits<double>::quiet_NaN();  // NaN without TV
    double wiener_nsr = 0;  // the NSR both Wiener decodes used (tuned or given)
};

// Distances from `from` to `to` (to may be inf) in `steps` >= 2 points equally spaced in 1/u
// (equal pitch steps); InvalidInput naming `from_m`, `to_m` or `steps` otherwise.
std::vector<double> depth_range(double from_m, double to_m, int steps);

// One record per distance (each checked: > f' when there is a lens, M(u) != 0; no two within
// 1e-6 of each other, design/optics/distance_list).
std::vector<DepthRecord> depth_analysis(const Mask& mask, const std::vector<double>& distances_m,
                                        const DepthOptions& options);

}  // namespace pinmask
