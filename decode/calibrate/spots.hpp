// Spot detection in a point-source capture (docs/design.md section 3, decode/calibrate/).
// Coordinates: index coordinates, x = column, y = row, pixel (r, c) has its centre at (c, r).
// The background is the frame's median and the noise its scaled median absolute deviation
// (robust: the spots cover a small fraction of the frame). A spot is an 8-connected component of
// pixels whose 3 x 3 box mean exceeds background + threshold_sigmas * sigma / 3 (the box mean of
// pure noise has sigma / 3); its centroid and flux come from the raw, background-subtracted
// pixels of its bounding box grown by one pixel.
#pragma once

#include <limits>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask::calibrate {

struct Background {
    double level = 0.0;  // median of the frame
    double sigma = 0.0;  // 1.4826 * median absolute deviation (the Gaussian sigma)
};

// Median and MAD of every pixel. Throws InvalidInput for an empty or non-finite plane.
Background estimate_background(const Plane& image);

// Median of a list (copy; empty -> 0).
double median_of(std::vector<double> values);

struct SpotOptions {
    double threshold_sigmas = 6.0;  // detection threshold on the 3 x 3 mean, in noise sigmas
    int min_area_px = 3;            // smaller components are noise
    // Second threshold relative to the spots: background + this fraction of the median spot
    // peak (3 x 3 mean) above background, when higher than the noise threshold. Keeps the
    // diffraction tails of neighbouring spots (Fresnel kernels) from joining them at high SNR.
    double relative_threshold = 0.25;
    double saturation_level = std::numeric_limits<double>::infinity();  // raw counts
    // The raw capture the saturation level applies to (before a dark frame was subtracted);
    // null: the image searched.
    const Plane* raw = nullptr;
};

struct Spot {
    double x = 0.0, y = 0.0;  // centroid (index coordinates)
    double flux = 0.0;        // background-subtracted sum over the grown bounding box
    double peak = 0.0;        // largest raw value
    int area_px = 0;          // pixels of the component
    int row0 = 0, row1 = 0, col0 = 0, col1 = 0;  // bounding box, inclusive
    bool saturated = false;                      // a pixel >= saturation_level
};

// Spots in scan order of their first pixel. Two passes: components above the noise threshold
// give the median peak; the components above the higher of the two thresholds are the spots.
std::vector<Spot> detect_spots(const Plane& image, const Background& background,
                               const SpotOptions& options = {});

}  // namespace pinmask::calibrate
