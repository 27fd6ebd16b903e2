#include "design/optics/image_plane.hpp"

#include <cmath>
#include <limits>

namespace pinmask {

double image_distance_at_u_m(const Camera& c) {
    if (std::isinf(c.lens_focal_m)) return std::numeric_limits<double>::infinity();
    const double inv_u = std::isinf(c.object_distance_m) ? 0.0 : 1.0 / c.object_distance_m;
    return 1.0 / (1.0 / c.lens_focal_m - inv_u);
}

double diffraction_first_zero_px(const Camera& c) {
    return c.wavelength_m * c.sensor_distance_m / (c.pinhole_m * c.pixel_pitch_m);
}

}  // namespace pinmask
