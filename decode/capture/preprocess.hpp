// Preprocessing of lensless captures as the DiffuserCam tutorial describes it (Waller Lab,
// DiffuserCam-Tutorial GD/ADMM notebooks; see data/real/*/README.md): a scalar background
// taken from a small patch near the top-left corner of the PSF and subtracted from both the PSF
// and the capture, k rounds of 2 x 2 box averaging, and division of each by its own L2 norm
// (one factor over a colour image's channels, channels_l2_norm).
// Values are sensor counts in, dimensionless out (after normalisation).
#pragma once

#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

// The tutorial's background patch: rows and columns 5 .. 14 (0-based, inclusive), 10 x 10.
inline constexpr int kCornerPatchStart = 5;
inline constexpr int kCornerPatchSize = 10;

// Mean of the size x size patch whose top-left pixel is (row0, col0). Throws InvalidInput when
// the patch does not fit inside the plane (naming the patch and the plane size).
double patch_mean(const Plane& p, int row0, int col0, int size);

// The tutorial's background: patch_mean(p, 5, 5, 10).
double corner_background(const Plane& p);

// One round of 2 x 2 box averaging: out(r, c) = mean of in(2r .. 2r+1, 2c .. 2c+1). An odd last
// row or column has no partner and is dropped (out is floor(R/2) x floor(C/2)). Throws
// InvalidInput when the plane is smaller than 2 x 2.
Plane box_downsample_2x(const Plane& p);

// `rounds` rounds of box_downsample_2x (a factor 2^rounds per side); rounds = 0 copies.
// Throws InvalidInput for rounds < 0 or when a round would leave fewer than 1 x 1 pixels.
Plane box_downsample(const Plane& p, int rounds);

// One factor for every channel of an image, so that the channels keep their ratios (a colour
// PSF's ratios are the sensor's response to a white source; a capture's, the scene's colour):
// the root mean square of the channels' L2 norms, and the mean of their sums (a mono image: its
// own norm, its own sum). InvalidInput naming `what` unless finite and > 0.
double channels_l2_norm(const std::vector<Plane>& channels, const char* what);
double channels_mean_sum(const std::vector<Plane>& channels, const char* what);

}  // namespace pinmask
