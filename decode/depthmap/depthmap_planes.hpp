// The planes of a mask's sweep when a face leaves the range or the count out, and the depth
// resolution the camera has over the range (docs/depth.md sections 1 and 5).
//   Range: the design's usable object distances (design/optics/working_distance: the distances
//   whose pitch stays within 1 px of the pitch at the camera's u across one period, what
//   `pinmask design` prints), each end only where the face gave none. An end clamped to the
//   lens' focal length moves just beyond it (an object at f' is refused).
//   Resolvable step in t = 1/u: the larger of one pixel of pattern change across the tiled mask,
//   w / (f N_t d) (the accuracy the sweep reaches, docs/depth.md section 4), and the Cramer-Rao
//   FWHM 2.355 sigma_t of a point source on the axis (optimize/metrics/depth_fisher) at the middle
//   of the range in 1/u, kDepthmapResolutionPhotons photo-electrons, over the capture's frame.
//   Count: planes one resolvable step apart, ceil((1/from - 1/to) / step) + 1, at least 2 and at
//   most kDepthmapMaxDefaultPlanes (beyond, the planes are farther apart than the step: `capped`).
//   Resolution at a distance u: u^2 times the resolvable step (inf at u = inf).
#pragma once

#include <optional>

#include "design/pattern/mask.hpp"

namespace pinmask {

// The light of the point source whose Cramer-Rao bound sets the resolvable step (depth_fisher's
// default, the figure of docs/depth.md section 4).
inline constexpr double kDepthmapResolutionPhotons = 20000.0;
inline constexpr int kDepthmapMaxDefaultPlanes = 64;

struct DepthmapPlaneChoice {
    double from_m = 0, to_m = 0;  // to_m may be inf
    int steps = 0;
    bool from_given = false, to_given = false, steps_given = false;
    double spacing_inverse_per_m = 0;     // (1/from - 1/to) / (steps - 1)
    double one_pixel_inverse_per_m = 0;   // w / (f N_t d)
    double crb_fwhm_inverse_per_m = 0;    // 2.355 sigma_t at the middle of the range
    double crb_distance_m = 0;            // the distance it was taken at
    double resolvable_inverse_per_m = 0;  // the larger of the two
    double resolution_near_m = 0;         // from^2 x resolvable step
    double resolution_far_m = 0;          // to^2 x resolvable step (inf at to = inf)
    bool capped = false;                  // the count was cut to kDepthmapMaxDefaultPlanes
    // The planes are closer than the resolvable step (a given count, or range): neighbouring
    // planes are not told apart by the camera, so a label is read to about step / spacing planes.
    bool finer_than_resolvable = false;
};

// from_m, to_m, steps: the face's values (nullopt: the default above); rows x cols the capture's
// frame. InvalidInput naming from_m / to_m (a given end on the wrong side of the defaulted one,
// or inside the focal length) or steps.
DepthmapPlaneChoice choose_depthmap_planes(const Mask& mask, std::optional<double> from_m,
                                           std::optional<double> to_m, std::optional<int> steps,
                                           int rows, int cols);

}  // namespace pinmask
