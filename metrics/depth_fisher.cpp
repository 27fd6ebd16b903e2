#include "metrics/depth_fisher.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/field_names.hpp"
#include "core/units.hpp"
#include "design/psf_exact.hpp"
#include "design/working_distance.hpp"

namespace pinmask {

void DepthFisherOptions::validate() const {
    if (!(photons > 0.0) || !std::isfinite(photons)) {
        throw invalid_field(field_ref("photons"), std::to_string(photons),
                            "must be finite and > 0");
    }
    if (!(read_noise_e >= 0.0) || !std::isfinite(read_noise_e)) {
        throw invalid_field(field_ref("read_noise"), std::to_string(read_noise_e),
                            "must be finite and >= 0");
    }
    if (rows < 0 || cols < 0) {
        throw invalid_field("size", std::to_string(rows) + "x" + std::to_string(cols),
                            "must be >= 0 (0: the sensor)");
    }
}

DepthFisher depth_fisher(const Mask& mask, double u, const DepthFisherOptions& o) {
    o.validate();
    if (!std::isfinite(u)) {
        throw invalid_field(field_ref("object_distance_m"), format_length(u),
                            "must be finite (the bound is in 1/u around u)");
    }
    check_object_distance(mask.camera, u, "object_distance_m");
    const Camera& c = mask.camera;
    const double nt_d = static_cast<double>(mask.pattern.n) *
                        std::max(mask.pattern.tiles_rows, mask.pattern.tiles_cols) * c.pinhole_m;
    DepthFisher out;
    out.object_distance_m = u;
    out.one_pixel_inverse_per_m = c.pixel_pitch_m / (c.sensor_distance_m * nt_d);
    const double t = 1.0 / u, dt = out.one_pixel_inverse_per_m / 20.0;
    // Stay on the object side of the lens: t + dt must keep u > f'.
    if (std::isfinite(c.lens_focal_m) && !(t + dt < 1.0 / c.lens_focal_m)) {
        throw invalid_field(field_ref("object_distance_m"), format_length(u),
                            "is too close to the focal length for the difference step");
    }
    ExactPsfOptions eo;
    eo.rows = o.rows;
    eo.cols = o.cols;
    eo.object_distance_m = u;
    const Plane h = exact_psf(mask, eo);
    eo.object_distance_m = 1.0 / (t + dt);
    const Plane hp = exact_psf(mask, eo);
    const Plane hm = t > dt ? (eo.object_distance_m = 1.0 / (t - dt), exact_psf(mask, eo))
                            : (eo.object_distance_m = u, h);
    const double step = t > dt ? 2.0 * dt : dt;
    const Plane dmu = o.photons * (hp - hm) / step;
    const Plane var = o.photons * h + o.read_noise_e * o.read_noise_e;
    double info = 0.0;
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        if (var.data()[i] > 0.0) info += dmu.data()[i] * dmu.data()[i] / var.data()[i];
    }
    out.fisher_inverse_m2 = info;
    out.crb_inverse_per_m = info > 0.0 ? 1.0 / std::sqrt(info) : INFINITY;
    out.crb_distance_m = u * u * out.crb_inverse_per_m;
    return out;
}

}  // namespace pinmask
