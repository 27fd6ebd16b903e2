// The PSF in exact geometry: what the camera records from a point source on the axis at object
// distance u, over a rows x cols sensor window centred on the optical axis (docs/design.md section 2,
// Eq. (3) of the paper). Notation as design/optics/camera.hpp; N_t = n * tiles cells per side of
// the tiled mask, M(u) = 1 - f/f' + f/u, pitch = d |M(u)| / w pixels (fractional).
//   A pinhole in mask cell (i, j) (row, col of the tiled mask, 0-based) sits at
//   s = ((i + 1/2) - N_t/2, (j + 1/2) - N_t/2) d from the mask centre; its spot centre lands at
//   q = M(u) s on the sensor (Eq. (3): image separation = (1 - f/f' + f/u) x mask separation),
//   i.e. at the continuous pixel coordinate rows/2 + q_row / w (pixel k covers [k, k + 1)).
//   Box kernel (geometric, the same at every wavelength): each spot is the square of side
//   |M(u)| d / w pixels centred exactly at its spot centre, integrated over the pixels in closed
//   form (design/psf/kernel box_pixel_profile_at), so its size and position both follow u.
//   Other kernels: the single-pinhole kernel is design/psf/kernel's for the camera at u (its
//   pixel-integrated values at the mask's integer pixels per cell, continuous centre ppc/2 from its
//   cell corner) over its own support: not cut to one period as the cyclic PSF's kernel is, moved
//   to the spot centre by area resampling: the fractional shift spreads each kernel pixel over the
//   two (per axis) sensor pixels it overlaps, in proportion to the overlap, so the values' sum and
//   centroid move exactly with the shift.
// Each pinhole weighs 1/K (K = pinholes of the basic pattern), as in design/psf/psf, so one period
// of the exact PSF sums to about 1; spots off the window are cut (the sum says how much is kept).
// The integer-model PSF (design/psf/psf) is the decoder's model; this one is what the sensor
// records.
#pragma once

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask {

struct ExactPsfOptions {
    double object_distance_m = 0;  // u (> f' when there is a lens; inf allowed)
    int rows = 0;                  // window size in pixels; 0 = the camera's sensor
    int cols = 0;
    KernelOptions kernel;
};

// The spot centre of tiled-mask cell (i, j) in continuous pixel coordinates (row, col) for the
// window rows x cols, by the relations above.
struct SpotCentre {
    double row = 0;
    double col = 0;
};
SpotCentre exact_spot_centre(const Mask& mask, double object_distance_m, int rows, int cols,
                             int cell_row, int cell_col);

// The exact-geometry PSF. Throws InvalidInput naming the field for an object inside the focal
// length, a window below 1 pixel, M(u) = 0 (every pinhole on one spot), a pattern without
// pinholes; ResourceLimit when the window exceeds the memory bound.
Plane exact_psf(const Mask& mask, const ExactPsfOptions& options);

}  // namespace pinmask
