// The optics calculator: every figure of the design report (docs/design.md section 2) from a Camera
// and the pattern geometry. Notation as design/optics/camera.hpp; M = magnification, p =
// image-plane cell pitch (= geometric spot of one pinhole), z_eff = effective Fresnel distance, N_F
// = Fresnel number, s_max = n d = largest pinhole separation in the basic pattern. Which object
// distance each figure uses:
//   - names without "_at_u" are design values for a distant object (u -> inf), as the paper
//     quotes them: M = 1 - f/f', p = |M| d, 1/z_eff = 1/f - 1/f' (z_eff = f f'/(f' - f));
//   - names with "_at_u" use the camera's u (point source at u): M = 1 - f/f' + f/u,
//     1/z_eff(u) = 1/f - (1/f' - 1/u). The kernel models use these (kernel.hpp).
// Infinite values are legal results: z_eff = inf when 1/z_eff = 0 (f = f', u = inf: the
// Fraunhofer limit), u_min / pinhole sizes = inf when M = 0. f' = inf means no lens (z_eff = f).
#pragma once

#include <string>

#include "design/optics/camera.hpp"
#include "design/pattern/pattern.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask {

// The pattern geometry the report needs (the pinhole positions do not enter).
struct PatternGeometry {
    int n = 16;      // grid n x n cells
    int holes = 20;  // K open cells
    int tiles_rows = 2;
    int tiles_cols = 2;
};

PatternGeometry geometry_of(const Pattern& pattern);

// Throws InvalidInput naming the field: 1 <= n <= kMaxGrid, 0 <= holes <= n^2, tiles >= 1.
void validate(const PatternGeometry& g);

struct OpticsOptions {
    // Shift invariance holds while the object term f s_max / u is at most this many pixels.
    double lsi_tolerance_px = 1.0;
};

// The LSI tolerance's range, for every face. Below a millionth of a pixel no sensor or PSF
// model resolves the mismatch, and the object-distance bound f s_max / (t w) only grows
// towards infinity (1e-320, a denormal, overflows it); above 1000 px the mismatch exceeds a
// whole period of any real sensor and says nothing.
inline constexpr double kMinLsiTolerancePx = 1e-6;
inline constexpr double kMaxLsiTolerancePx = 1000.0;

// Throws InvalidInput naming `lsi_tolerance_px` unless kMinLsiTolerancePx <= t <=
// kMaxLsiTolerancePx.
void validate_lsi_tolerance(double t_px);

struct OpticsReport {
    Camera camera;
    PatternGeometry geometry;
    OpticsOptions options;

    double magnification = 0;       // 1 - f/f'; negative past focus
    double magnification_at_u = 0;  // 1 - f/f' + f/u
    double geometric_spot_m = 0;    // |M| d: the image-plane cell pitch p
    double geometric_spot_at_u_m = 0;
    // p / w for a distant object (u = inf: the paper's 7.94); every face reports pixels per cell
    // at the working distance u (pixels_per_cell_at_u) under the name pixels_per_cell.
    double pixels_per_cell_at_inf = 0;
    double pixels_per_cell_at_u = 0;
    long long integer_pixels_per_cell = 1;    // n_px: nearest integer to p / w, at least 1
    double pinhole_for_integer_pixels_m = 0;  // d = n_px w / |M| (inf when M = 0)
    double optimum_pinhole_m = 0;             // 1.56 sqrt(lambda f)
    double fresnel_number = 0;                // d^2 / (4 lambda f), no lens
    double effective_distance_m = 0;          // z_eff, u -> inf (inf when f = f')
    double effective_distance_at_u_m = 0;     // z_eff(u)
    double fresnel_number_with_lens = 0;      // d^2 / (4 lambda |z_eff|), 0 when z_eff = inf
    double fresnel_number_with_lens_at_u = 0;
    double max_separation_m = 0;           // s_max = n d
    double lsi_min_object_distance_m = 0;  // u_min = f s_max / (tolerance w)
    double lsi_mismatch_px = 0;            // f s_max / (u w); 0 at u = inf
    long long psf_size_px = 0;             // n * n_px
    double periods_on_sensor_cols = 0;     // sensor width / PSF size (fractional)
    double periods_on_sensor_rows = 0;
    double mask_width_m = 0;                           // n * tiles_cols * d
    double mask_height_m = 0;                          // n * tiles_rows * d
    double open_fraction = 0;                          // K / n^2
    double light_gain = 0;                             // K: light over one pinhole of the same size
    KernelModel kernel_model = KernelModel::kFresnel;  // resolved (auto applied)
    std::string kernel_reason;

    // True when the LSI model holds at the camera's u within options.lsi_tolerance_px.
    bool is_shift_invariant() const { return lsi_mismatch_px <= options.lsi_tolerance_px; }
};

// The report; `requested` = kAuto resolves by choose_kernel_model(fresnel_number_with_lens_at_u).
// Validates camera, geometry and options (InvalidInput naming the field).
OpticsReport compute_optics(const Camera& camera, const PatternGeometry& geometry,
                            KernelModel requested = KernelModel::kAuto,
                            const OpticsOptions& options = {});

// 1/z_eff(u) = 1/f - 1/f' + 1/u (1/m); 0 in the Fraunhofer limit, negative past focus.
double inverse_effective_distance_at_u(const Camera& camera);
// M(u) = f / z_eff(u) = 1 - f/f' + f/u.
double magnification_at_u(const Camera& camera);
// N(u) = d^2 |1/z_eff(u)| / (4 lambda): the Fresnel number the kernel models use.
double fresnel_number_at_u(const Camera& camera);
// Image-plane cell pitch in sensor pixels for a distant object, |M| d / w with M = 1 - f/f'
// (f' = inf: d / w): OpticsReport::pixels_per_cell_at_inf, the design value the paper quotes
// (7.94).
double design_pixels_per_cell(const Camera& camera);

}  // namespace pinmask
