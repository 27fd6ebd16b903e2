// The camera at its working distance u (docs/design.md section 2, "Working distance"). Notation as
// design/optics/camera.hpp and design/optics/optics.hpp; M(u) = 1 - f/f' + f/u, N = a whole number
// of pixels per cell (the decoder's integer cyclic model), n = grid, s_max = n d (widest pinhole
// separation of one period), t = the LSI tolerance in pixels.
//   pitch(u)      = d |M(u)| / w                      pixels per cell at u (fractional)
//   d(N, u)       = N w / |M(u)|                      pinhole for N whole pixels per cell AT u
//   period(u)     = n pitch(u)                        one period of the image, pixels
//   mismatch(u)   = n |pitch(u) - N|                  pitch error across one period against the
//                                                     N-pixel model, pixels
//   PSF size      = n N                               one period of the decoder's model at u
//   range         = {u' : f s_max |1/u' - 1/u| / w <= t}: the object distances whose pitch stays
//                   within t pixels (across one period) of the pitch at u. For a pinhole solved
//                   for N at u the pitch at u is N, so this is where the integer model holds.
//                   u_far = inf when 1/u <= t w / (f s_max); u_near is clamped to f' (objects
//                   inside the focal length are refused, see check_object_distance).
//   optima        lensless 1.56 sqrt(lambda f) (the paper's rule); with the lens the diffraction
//                 distance is z_eff(u) = 1/(1/f - 1/f' + 1/u) and the same balance of spot size
//                 and diffraction gives 1.56 sqrt(lambda |z_eff(u)|) (inf when z_eff = inf).
//   spot spread   main lobe of one pinhole's spot over its cell: the Fraunhofer lobe 2 lambda
//                 |z_eff| / d against the geometric cell d, i.e. 1/(2 N_F(u)), at least 1.
#pragma once

#include <optional>
#include <string>

#include "design/optics/camera.hpp"
#include "design/optics/optics.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct WorkingDistanceOptions {
    double lsi_tolerance_px = 1.0;  // t, finite and > 0
    int pixels_per_cell = 0;        // N; 0 = the nearest whole number to pitch(u), at least 1
};

// Throws InvalidInput naming the field and the rule.
void validate(const WorkingDistanceOptions& options);

// Spots spreading wider than this many cells overlap their neighbours' cells: the design table
// warns ("more than about one cell").
inline constexpr double kSpotSpreadWarnCells = 1.0;

struct WorkingDistance {
    double object_distance_m = 0;
    double pixels_per_cell_at_u = 0;           // pitch(u) for the camera's d
    long long pixels_per_cell = 1;             // N
    double pinhole_for_pixels_per_cell_m = 0;  // d(N, u)
    double period_px = 0;                      // period(u)
    double lsi_mismatch_px = 0;                // mismatch(u) against N
    double lsi_tolerance_px = 1;               // t
    long long psf_size_px = 1;                 // n N: one period of the decoder's model at u
    double periods_on_sensor_cols = 0;         // sensor width / (n N)
    double periods_on_sensor_rows = 0;
    double range_near_m = 0;  // usable object-distance range (far may be inf)
    double range_far_m = 0;
    bool range_near_clamped_to_focal = false;  // u_near = f' (the tolerance reaches further)
    double optimum_pinhole_lensless_m = 0;     // 1.56 sqrt(lambda f)
    double optimum_pinhole_with_lens_m = 0;    // 1.56 sqrt(lambda |z_eff(u)|), inf at z_eff inf
    double fresnel_number_with_lens_at_u = 0;  // d^2 / (4 lambda |z_eff(u)|)
    double spot_spread_cells = 1;              // max(1, 1 / (2 N_F(u))), inf when N_F = 0

    bool spreads_beyond_cell() const { return spot_spread_cells > kSpotSpreadWarnCells; }
    // The N-pixel model holds at u: mismatch(u) within the tolerance.
    bool is_shift_invariant() const { return lsi_mismatch_px <= lsi_tolerance_px; }
};

// Throws InvalidInput when the object sits inside the lens' focal length (finite f', u <= f'),
// naming `field` (the caller's name for it: a face passes its own spelling, a library a
// field_ref) and both values.
void check_object_distance(const Camera& camera, double object_distance_m,
                           const char* field = "object_distance_m");

// pitch(u) for the camera's pinhole at the camera's own u.
double pixels_per_cell_at(const Camera& camera, double object_distance_m);

// Why the camera's cells are too small for its sensor, or nullopt: when one cell images to less
// than half a pixel at the camera's u (0 < pitch(u) < 0.5), the nearest whole number of pixels
// per cell is 0 and every whole-pixel model uses 1, so the PSF and the decoder would describe
// another camera. The message names the camera fields that set the pitch. f = f' with u = inf
// (pitch 0) is the zero-magnification case design/psf/kernel_validity already reports.
std::optional<std::string> sub_pixel_cells(const Camera& camera);

// d(N, u) at the camera's u; InvalidInput when M(u) = 0 (f = f' with u = inf: z_eff infinite,
// every pinhole images to the same spot) or N < 1.
double pinhole_for_pixels_per_cell(const Camera& camera, long long pixels_per_cell);

// The mask refocused to object distance u (decode --object-distance): the camera's u set to u,
// pixels per cell the nearest whole number to pitch(u) (at least 1), kernel unchanged (its models
// evaluate at the camera's u). InvalidInput for an object inside the focal length.
Mask mask_at_distance(const Mask& mask, double object_distance_m);

// Refocusing to u (decode --object-distance) keeps the integer torus only while the pitch at u
// is this close to a whole number across one period (n |pitch(u) - N| px); beyond, the torus
// would misplace the pinholes' images by that much and the exact-geometry PSF is used instead.
inline constexpr double kRefocusWholeTolerancePx = 0.25;

struct RefocusGeometry {
    double pitch_px = 0;          // pitch(u)
    long long whole_px = 1;       // N = the nearest whole number (at least 1)
    double mismatch_px = 0;       // n |pitch(u) - N|
    bool exact_geometry = false;  // mismatch above kRefocusWholeTolerancePx
};

// How a mask decodes an object at u (InvalidInput for an object inside the focal length).
RefocusGeometry refocus_geometry(const Mask& mask, double object_distance_m);

// Everything above for the camera at its u; validates camera, geometry, options and the object
// distance (InvalidInput naming the field).
WorkingDistance compute_working_distance(const Camera& camera, const PatternGeometry& geometry,
                                         const WorkingDistanceOptions& options = {});

}  // namespace pinmask
