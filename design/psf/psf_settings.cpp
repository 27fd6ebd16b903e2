#include "design/psf/psf_settings.hpp"

#include <cmath>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/input_file.hpp"
#include "core/units/units.hpp"
#include "design/optics/working_distance.hpp"

namespace pinmask {

void check_kernel_settings(const std::string& kernel, const std::string& kernel_path) {
    if (kernel == "measured" && kernel_path.empty()) {
        throw invalid_field(field_ref("kernel"), "measured",
                            "needs " + field_ref("kernel_path") + " FILE");
    }
    if (kernel != "measured" && !kernel_path.empty()) {
        throw invalid_field(field_ref("kernel_path"), kernel_path,
                            "only used with " + field_ref("kernel") + " measured");
    }
    // The kernel file is read only when a PSF is made: a path that cannot be read is refused
    // here, not by the later command that reads it.
    if (kernel == "measured") {
        if (const auto problem = input_file_problem(kernel_path))
            throw invalid_field(field_ref("kernel_path"), kernel_path, *problem);
    }
}

PsfSpec resolve_psf_spec(const PsfSettings& o, const Camera& c) {
    check_kernel_settings(o.kernel, o.kernel_path);
    PsfSpec spec;
    spec.kernel.model = o.kernel;
    spec.kernel.measured_path = o.kernel_path;
    if (o.pixels_per_cell) {
        if (*o.pixels_per_cell < 1) {
            throw invalid_field(field_ref("pixels_per_cell"), std::to_string(*o.pixels_per_cell),
                                "must be >= 1");
        }
        spec.pixels_per_cell = *o.pixels_per_cell;
        return spec;
    }
    const double design = pixels_per_cell_at(c, c.object_distance_m);
    const double rounded = std::round(design);
    if (!(rounded >= 1.0) || rounded > 1e6) {
        std::ostringstream v;
        v << design;
        throw invalid_field(
            "pixels per cell at u (d |1 - f/f' + f/u| / w)", v.str(),
            "rounds to less than 1 pixel (f = " + format_length(c.sensor_distance_m) +
                ", f' = " + format_length(c.lens_focal_m) + "): give " +
                field_ref("pixels_per_cell") + " explicitly");
    }
    spec.pixels_per_cell = static_cast<int>(rounded);
    return spec;
}

}  // namespace pinmask
