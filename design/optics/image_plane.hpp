// Two figures of the image plane the design report prints beside the optics report (notation as
// design/optics/camera.hpp):
//   v            the thin lens' image of the object at u: 1/v = 1/f' - 1/u (the thin-lens
//                equation, the paper's Eq. (2)): where a lens camera would put its sensor; the
//                coded pinhole lens puts it at f < v. f' at u = inf; +inf without a lens
//                (f' = inf: no image forms).
//   first zero   one pinhole's Fraunhofer (sinc^2) spot, centre to first zero on the sensor:
//                lambda z_eff / d at the effective distance z_eff, magnified by f / z_eff, so
//                lambda f / (d w) pixels at every u and f'.
#pragma once

#include "design/optics/camera.hpp"

namespace pinmask {

double image_distance_at_u_m(const Camera& camera);

double diffraction_first_zero_px(const Camera& camera);

}  // namespace pinmask
