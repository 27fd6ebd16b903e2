// pinmask depthmap: a depth map, its confidence and an all-in-focus image from one capture of a
// pinhole-array lens camera, by a plane sweep over object distance.
//   1. For each candidate distance u_k: the Wiener estimate with the exact-geometry PSF at u_k and
//      the local energy of its residual (depthmap/sweep_cost).
//   2. depthmap/refine: the lowest-cost plane per pixel, refined between planes by a parabola in
//      1/u, and a confidence.
//   3. All-in-focus: each pixel from the estimate of its winning plane.
//   4. The whole capture as one plane: the same refinement on the frame-mean costs.
// Interruption: `stop` is polled between planes; the result then holds the planes finished so far
// (interrupted = true), which is a complete sweep over a shorter list.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/image.hpp"
#include "design/mask.hpp"

namespace pinmask {

struct DepthmapOptions {
    std::vector<double> distances_m;  // candidate planes (>= 2, distinct, each > f'; inf allowed)
    double wiener_nsr = 0.01;         // scalar NSR of every decode (> 0)
    int window = 121;                 // odd box side of the consistency cost, px (>= 3)
    const std::atomic<bool>* stop = nullptr;
    // After each plane (done = planes finished, total).
    std::function<void(std::size_t done, std::size_t total)> progress;
    void validate() const;  // InvalidInput naming the field
};

struct DepthmapResult {
    std::vector<double> distances_m;     // the planes swept, sorted by increasing u
    Plane depth_m;                       // refined distance per pixel, metres
    Plane confidence;                    // [0, 1]
    Plane label;                         // winning plane index into distances_m
    Plane all_in_focus;                  // each pixel from its plane's Wiener estimate
    std::vector<double> plane_fraction;  // share of pixels won by each plane
    // The whole capture as one plane: the frame-mean cost per plane, and the distance where it is
    // lowest (refined by the parabola of depthmap/refine), with its confidence.
    std::vector<double> plane_cost;
    double capture_depth_m = 0;
    double capture_confidence = 0;
    // Summary of the maps: smallest, median (upper middle) and largest depth, median confidence.
    double depth_min_m = 0, depth_median_m = 0, depth_max_m = 0, confidence_median = 0;
    bool interrupted = false;
};

// capture: one channel (grey), finite, at least window x window. Throws InvalidInput naming the
// field; ResourceLimit when the planes' estimates do not fit the memory budget.
DepthmapResult depthmap(const Plane& capture, const Mask& mask, const DepthmapOptions& options);

}  // namespace pinmask
