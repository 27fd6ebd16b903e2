// Single-pinhole kernels on the sensor's pixel grid (docs/design.md section 2). Notation and the
// continuous profile h(N, v): design/psf/kernel_profile.hpp. Optics figures:
// design/optics/optics.hpp.
//
// Placement: along each axis the kernel's continuous centre is the centre of the image-plane
// cell, ppc/2 pixels from the cell's top-left corner (pixel k covers [k, k + 1)). values(i, j) is
// the pixel (origin_row + i, origin_col + j) counted from the cell's top-left pixel, so for even
// ppc the centre falls on a pixel corner and the support has an even width, for odd ppc on a pixel
// centre with an odd width.
//
// Pixel values are integrals of the continuous intensity over the pixel's area:
//   box        exact overlap lengths of the geometric spot (side |M(u)| d) with each pixel;
//   fraunhofer sinc^2 per axis, Gauss-Legendre panels (12 points, width <= 1/2 in v), exact to
//              rounding because the profile is band-limited (kernel_profile.hpp);
//   fresnel    the full profile h(N(u), v) the same way, N(u) = fresnel_number_at_u(camera).
// The support grows symmetrically from the centre until the kept 1-D energy of the continuous
// profile (normalised to 1 analytically) reaches KernelOptions::energy_fraction per axis, or the
// width reaches max_width_px. The sinc^2 tail falls as 1/v^2: keeping 99.9% needs |v| ~ 100,
// hundreds of pixels for the paper's camera, so the cap usually binds for fraunhofer/fresnel;
// Kernel::enclosed_energy and support_capped say what was kept. Values are then normalised to
// sum 1 (the cut tail is dropped, not folded back).
//
// Polychromatic: KernelSpec::wavelengths (wavelength_m, weight) gives the weighted sum of the
// normalised monochromatic kernels, weights normalised to sum 1; empty means the camera's band
// (design/optics/spectrum: the design wavelength alone when Camera::bandwidth_m is 0). A list
// beside a non-zero bandwidth_m is refused (InvalidInput naming bandwidth_m and the list). "auto"
// resolves per wavelength; when wavelengths disagree, fresnel is used for all.
//
// "paper-fig3b" is the paper's measured 8 x 8 kernel (its Fig. 3b, design/psf/paper_kernel.hpp),
// normalised to sum 1, covering the cell exactly (origin 0, 0); defined only for 8 pixels per
// cell (InvalidInput naming the 8 otherwise). It does not depend on the camera.
// "measured" reads KernelSpec::measured_path (core/image/image_io read_image), one channel, finite,
// sum > 0, normalised to sum 1; its central element (floor(rows/2), floor(cols/2)) is placed on
// the cell's pixel (floor(ppc/2), floor(ppc/2)) (exact centring when the sizes' parities match
// ppc's, otherwise the kernel sits half a pixel down/right).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/image/image.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask {

struct KernelOptions {
    double energy_fraction = 0.999;  // per axis, of the continuous profile; in (0, 1]
    int max_width_px = 1025;         // support cap per axis, >= 1
};

// Throws InvalidInput naming the field.
void validate(const KernelOptions& options);

// Largest pixels-per-cell value accepted anywhere (a 65536-pixel cell is already absurd).
inline constexpr int kMaxPixelsPerCell = 65536;

// A 1-D pixel-integrated profile: values[k] is pixel origin + k counted from the cell's first
// pixel. `enclosed` is the kept fraction of the continuous profile's energy (before any
// normalisation); `capped` says max_width_px stopped the growth.
struct PixelProfile {
    std::vector<double> values;
    int origin = 0;
    double enclosed = 1.0;
    bool capped = false;
};

// Geometric box of width spot_px pixels (>= 0; 0 is the limit of a point) centred at ppc/2:
// exact overlaps divided by the width.
PixelProfile box_pixel_profile(double spot_px, int pixels_per_cell, const KernelOptions& options);

// The same geometric box with its continuous centre at `centre_px` in absolute pixel
// coordinates (pixel k covers [k, k + 1)), any fraction: exact overlaps divided by the width, no
// resampling; origin is the absolute index of values[0]. A support wider than max_width_px keeps
// the max_width_px pixels around the centre's pixel (capped, enclosed < 1). Used by the
// exact-geometry PSF, whose spots sit at fractional positions and whose side follows u.
PixelProfile box_pixel_profile_at(double spot_px, double centre_px, const KernelOptions& options);

// Any normalised, even, band-limited profile h(v) (<= 1 cycle per unit v) integrated over pixels
// of width pixel_v = d w / (lambda f) in v, centred at ppc/2, support by energy (see above).
// Throws InvalidInput when a pixel spans so many fringes that the work would exceed ~5e7
// evaluations (pixel_v > ~4e6 / width), naming the wavelength-dependent quantity.
PixelProfile diffraction_pixel_profile(const std::function<double(double)>& h, double pixel_v,
                                       int pixels_per_cell, const KernelOptions& options);

struct Kernel {
    Plane values;  // sums to 1
    int origin_row = 0;
    int origin_col = 0;
    KernelModel model = KernelModel::kBox;  // resolved (never kAuto)
    std::string model_reason;               // why (auto's reason, or "requested")
    double enclosed_energy = 1.0;  // continuous 2-D energy kept before normalising (weighted)
    bool support_capped = false;
    std::vector<std::pair<double, double>> wavelengths;  // (m, weight summing to 1) used
    std::string source;                                  // measured: the file read
};

// The kernel of one pinhole for this camera and spec, at ppc pixels per cell
// (1..kMaxPixelsPerCell). Validates everything (InvalidInput naming the field).
Kernel make_kernel(const Camera& camera, const KernelSpec& spec, int pixels_per_cell,
                   const KernelOptions& options = {});

// A measured kernel from an in-memory plane (the "measured" model without a file): finite, sum > 0
// (InvalidInput naming `source` otherwise), normalised to sum 1, placed as described above.
Kernel measured_kernel(const Plane& values, int pixels_per_cell, const std::string& source);

}  // namespace pinmask
