#include "decode/depthmap/depthmap_planes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "optimize/metrics/depth_fisher.hpp"

namespace pinmask {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFwhmPerSigma = 2.355;

double inverse(double u) { return std::isinf(u) ? 0.0 : 1.0 / u; }

}  // namespace

DepthmapPlaneChoice choose_depthmap_planes(const Mask& mask, std::optional<double> from_m,
                                           std::optional<double> to_m, std::optional<int> steps,
                                           int rows, int cols) {
    DepthmapPlaneChoice c;
    c.from_given = from_m.has_value();
    c.to_given = to_m.has_value();
    c.steps_given = steps.has_value();
    if (!c.from_given || !c.to_given) {
        const WorkingDistance wd = compute_working_distance(mask.camera, geometry_of(mask.pattern));
        double near = wd.range_near_m;
        // An object at f' is refused (check_object_distance): the nearest plane lies just beyond.
        if (wd.range_near_clamped_to_focal) near = mask.camera.lens_focal_m * (1.0 + 1e-3);
        if (!c.from_given && c.to_given && !(*to_m > near)) {
            throw invalid_field(field_ref("to_m"), format_length(*to_m),
                                "must be farther than the design's nearest usable distance " +
                                    format_length(near) + " (the default of " +
                                    field_ref("from_m") + "): give " + field_ref("from_m") +
                                    " too");
        }
        if (c.from_given && !c.to_given && !(wd.range_far_m > *from_m)) {
            throw invalid_field(field_ref("from_m"), format_length(*from_m),
                                "must be nearer than the design's farthest usable distance " +
                                    format_length(wd.range_far_m) + " (the default of " +
                                    field_ref("to_m") + "): give " + field_ref("to_m") + " too");
        }
        c.from_m = c.from_given ? *from_m : near;
        c.to_m = c.to_given ? *to_m : wd.range_far_m;
    } else {
        c.from_m = *from_m;
        c.to_m = *to_m;
    }
    if (!(c.from_m > 0.0) || !std::isfinite(c.from_m)) {
        throw invalid_field(field_ref("from_m"), format_length(c.from_m), "must be finite and > 0");
    }
    if (!(c.to_m > c.from_m)) {
        throw invalid_field(field_ref("to_m"), format_length(c.to_m),
                            "must be greater than " + field_ref("from_m") + " (inf allowed)");
    }
    check_object_distance(mask.camera, c.from_m, "from_m");
    const double x0 = inverse(c.from_m), x1 = inverse(c.to_m);
    c.crb_distance_m = 2.0 / (x0 + x1);
    DepthFisherOptions fo;
    fo.photons = kDepthmapResolutionPhotons;
    fo.rows = rows;
    fo.cols = cols;
    const DepthFisher fisher = depth_fisher(mask, c.crb_distance_m, fo);
    c.one_pixel_inverse_per_m = fisher.one_pixel_inverse_per_m;
    c.crb_fwhm_inverse_per_m = kFwhmPerSigma * fisher.crb_inverse_per_m;
    c.resolvable_inverse_per_m = std::max(c.one_pixel_inverse_per_m, c.crb_fwhm_inverse_per_m);
    if (c.steps_given) {
        c.steps = *steps;
        if (c.steps < 2 || c.steps > 1000) {
            throw invalid_field(field_ref("steps"), std::to_string(c.steps),
                                "must be between 2 and 1000");
        }
    } else {
        const double planes = std::ceil((x0 - x1) / c.resolvable_inverse_per_m - 1e-9) + 1.0;
        c.capped = planes > kDepthmapMaxDefaultPlanes;
        c.steps = static_cast<int>(std::clamp(planes, 2.0, double(kDepthmapMaxDefaultPlanes)));
    }
    c.spacing_inverse_per_m = (x0 - x1) / (c.steps - 1);
    c.finer_than_resolvable = c.spacing_inverse_per_m < c.resolvable_inverse_per_m * (1.0 - 1e-9);
    c.resolution_near_m = c.from_m * c.from_m * c.resolvable_inverse_per_m;
    c.resolution_far_m = std::isinf(c.to_m) ? kInf : c.to_m * c.to_m * c.resolvable_inverse_per_m;
    return c;
}

}  // namespace pinmask
