// pinmask depthmap: a depth map, its confidence and an all-in-focus image from one capture of a
// pinhole-array lens camera, by a plane sweep over object distance.
//   1. For each candidate distance u_k: the Wiener estimate with the exact-geometry PSF at u_k and
//      the local energy of its residual (decode/depthmap/sweep_cost).
//   2. The labelling: with smooth = 0 the lowest-cost plane per pixel (winner-take-all); with
//      smooth > 0 the minimiser of the cost plus a smoothness penalty between neighbouring
//      pixels' planes, by semi-global aggregation along 8 paths (decode/depthmap/smooth_labels).
//      Then decode/depthmap/refine: a parabola in 1/u between planes, and the cost margin of the
//      chosen plane, mapped to a probability (decode/depthmap/calibrated_confidence).
//   3. All-in-focus: each pixel from the estimate of its winning plane.
//   4. The whole capture as one plane: the same refinement on the frame-mean costs, and on the
//      planes' evidence (the marginal likelihood of the capture).
// Interruption: `stop` is polled between planes; the result then holds the planes finished so far
// (interrupted = true), which is a complete sweep over a shorter list.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

// The smoothness weight that measured best on the scenes of docs/depth.md's table.
inline constexpr double kDepthmapDefaultSmooth = 8.0;

struct DepthmapOptions {
    std::vector<double>
        distances_m;  // candidate planes (>= 2, distinct by > 1e-6 relative, > f'; inf allowed)
    double wiener_nsr = 0.01;  // scalar NSR of every decode (> 0)
    int window = 121;          // odd box side of the consistency cost, px (>= 3)
    // Weight of the smoothness term (>= 0; 0: winner-take-all). A step of one plane between
    // neighbouring pixels costs smooth * s, a larger jump 2 smooth * s, where s is the mean
    // depth of the pixels' cost wells (decode/depthmap/smooth_labels cost_well_depth), so the
    // weight does not depend on the capture's brightness.
    double smooth = kDepthmapDefaultSmooth;
    const std::atomic<bool>* stop = nullptr;
    // After each plane (done = planes finished, total).
    std::function<void(std::size_t done, std::size_t total)> progress;
    void validate() const;           // InvalidInput naming the field
    void validate_settings() const;  // the settings other than distances_m
};

// One plane of a given PSF stack (measured or computed outside pinmask): its object distance
// and its PSF (at most the capture's size; centred as decode/solvers/psf2otf, normalised to sum 1
// here).
struct PsfStackPlane {
    double distance_m = 0;  // > 0, finite
    Plane psf;
};

struct DepthmapResult {
    std::vector<double> distances_m;  // the planes swept, sorted by increasing u
    Plane depth_m;                    // refined distance per pixel, metres
    // The probability that the pixel's depth lies within one plane spacing of the truth: its
    // cost margin mapped by decode/depthmap/calibrated_confidence (measured reliability:
    // docs/depth.md section 3c).
    Plane confidence;
    Plane cost_margin;   // (median cost - chosen plane's cost) / median cost, in [0, 1]
    Plane label;         // winning plane index into distances_m
    Plane all_in_focus;  // each pixel from its plane's Wiener estimate
    std::vector<double> plane_fraction;  // share of pixels won by each plane
    // The whole capture as one plane: the frame-mean cost per plane, and the distance where it is
    // lowest (refined by the parabola of decode/depthmap/refine), with its confidence.
    std::vector<double> plane_cost;
    double capture_depth_m = 0;
    double capture_confidence = 0;
    // The whole capture by the evidence instead (decode/depthmap/sweep_cost: the marginal
    // likelihood under a 1/f^2 scene prior): each plane's evidence, and the distance where it is
    // lowest (refined by the same parabola). docs/depth.md section 3b: on the real tilted target it
    // picks the plane that decodes the target, where the frame-mean cost picks the far end.
    std::vector<double> plane_evidence;
    double capture_evidence_depth_m = 0;
    // Summary of the maps: smallest, median (upper middle) and largest depth, median confidence.
    double depth_min_m = 0, depth_median_m = 0, depth_max_m = 0, confidence_median = 0;
    bool interrupted = false;
};

// Where the planes come from, as a face's arguments give it: the mask (from, to and steps
// optional: decode/depthmap/depthmap_planes's defaults) or a PSF stack (none of them), exactly
// one. InvalidInput naming the field at fault (mask, psf_stack, from_m, to_m, steps) otherwise.
void check_plane_source(bool mask, bool psf_stack, bool from, bool to, bool steps);

// capture: one channel (grey), finite, at least window x window. Throws InvalidInput naming the
// field; ResourceLimit when the planes' estimates do not fit the memory budget.
DepthmapResult depthmap(const Plane& capture, const Mask& mask, const DepthmapOptions& options);

// The same pipeline over a given PSF stack instead of the mask's exact geometry: the planes are
// the stack's distances (options.distances_m is not used). At least 2 planes, distances > 0,
// finite and distinct (by more than 1e-6 of the distance), PSFs finite, non-negative, with light,
// at most the capture's size; InvalidInput naming `psf_stack` otherwise.
DepthmapResult depthmap(const Plane& capture, const std::vector<PsfStackPlane>& stack,
                        const DepthmapOptions& options);

}  // namespace pinmask
