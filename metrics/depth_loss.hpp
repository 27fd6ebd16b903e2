// Depth analysis of a mask (pinmask depth): for each object distance u, the figures of
// design/working_distance (pitch, period, LSI mismatch against the mask's whole pixels per cell)
// and the PSNR lost when the capture the camera records at u (exact geometry, design/psf_exact:
// scene (*) exact PSF, linear convolution, simulate/simulate linear_capture) is decoded with the
// mask's integer cyclic PSF, for Wiener and TV-L2 (decode/decoder decode_plane).
//   reference PSNR: the cyclic capture scene (*) A (the decoder's own model) with the same noise
//                   draw, decoded the same way;
//   exact PSNR:     on an even window holding the tiled mask's spots and the scene (the axis on a
//                   pixel corner), the centred m x m crop of the exact capture (the decoder's
//                   default window), decoded; the scene then appears cyclically shifted (its centre
//                   sits on the optical axis, not on the crop's centre), so both decodes are
//                   compared with the scene after the integer cyclic shift that maximises their
//                   correlation;
//   loss = reference PSNR - exact PSNR, dB, averaged over the scenes.
// Noise: Gaussian at snr_db from each capture's own mean square (inf: noiseless), one seeded draw
// per scene shared by both captures.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "design/mask.hpp"

namespace pinmask {

struct DepthOptions {
    std::vector<std::string> scenes{"letter-R", "natural"};  // simulate/scenes names
    double snr_db = 30.0;                                    // inf: noiseless
    double wiener_nsr = 0.01;                                // as pinmask score's default
    double tv_lambda = 1e-3;                                 // as pinmask score's default
    int tv_iterations = 100;                                 // >= 1
    bool with_tv = true;
    std::uint64_t seed = 1;
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
};

// Distances from `from` to `to` (to may be inf) in `steps` >= 2 points equally spaced in 1/u
// (equal pitch steps); InvalidInput naming `from_m`, `to_m` or `steps` otherwise.
std::vector<double> depth_range(double from_m, double to_m, int steps);

// One record per distance (each checked: > f' when there is a lens, M(u) != 0).
std::vector<DepthRecord> depth_analysis(const Mask& mask, const std::vector<double>& distances_m,
                                        const DepthOptions& options);

}  // namespace pinmask
