#include "design/optics/default_pinhole.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"

namespace pinmask {
namespace {

// The paper's balance of geometric spot and diffraction (design/optics/working_distance, optics).
constexpr double kOptimumPinholeFactor = 1.56;

double optimum_pinhole_m(const Camera& c) {
    const double inv_z = std::fabs(inverse_effective_distance_at_u(c));
    if (inv_z == 0.0) return std::numeric_limits<double>::infinity();
    return kOptimumPinholeFactor * std::sqrt(c.wavelength_m / inv_z);
}

std::string g(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace

DefaultPinhole default_pinhole(const Camera& c) {
    DefaultPinhole out;
    out.optimum_m = optimum_pinhole_m(c);
    const double m = std::fabs(magnification_at_u(c));
    if (!std::isfinite(out.optimum_m) || m == 0.0) {
        out.pinhole_m = c.pinhole_m;
        out.note = "no " + field_ref("pinhole_m") + " given, and this camera has no finite " +
                   "optimum pinhole (z_eff is infinite: f = f' with u = inf): keeping d = " +
                   format_length(c.pinhole_m) + "; give " + field_ref("pinhole_m");
        return out;
    }
    const double pitch_px = out.optimum_m * m / c.pixel_pitch_m;
    out.pixels_per_cell = static_cast<long long>(std::max(1.0, std::round(pitch_px)));
    out.pinhole_m =
        pinhole_on_grid_m(pinhole_for_pixels_per_cell(c, out.pixels_per_cell), kDefaultFabGridNm);
    out.solved = true;
    out.note = "no " + field_ref("pinhole_m") +
               " given: using d = " + format_length(out.pinhole_m) + ", the pinhole for " +
               std::to_string(out.pixels_per_cell) +
               " whole pixels per cell at u nearest the diffraction optimum 1.56 sqrt(lambda "
               "|z_eff(u)|) = " +
               format_length(out.optimum_m) + " (" + g(pitch_px) + " px per cell)";
    if (out.pinhole_m > kFarFromOptimumFactor * out.optimum_m)
        out.note += "; one pixel per cell is already " + g(out.pinhole_m / out.optimum_m) +
                    "x the optimum: the pixels are coarse for this optics";
    out.note += "; give " + field_ref("pinhole_m") + " to choose another";
    return out;
}

std::string far_from_optimum_note(const Camera& c) {
    const double opt = optimum_pinhole_m(c);
    if (!std::isfinite(opt)) return "";
    const double ratio = c.pinhole_m / opt;
    if (ratio <= kFarFromOptimumFactor && ratio >= 1.0 / kFarFromOptimumFactor) return "";
    return "the solve starts from d = " + format_length(c.pinhole_m) + ", " + g(ratio) +
           "x the diffraction optimum 1.56 sqrt(lambda |z_eff(u)|) = " + format_length(opt) +
           " for this camera, and keeps that start's pitch; give " + field_ref("pinhole_m") +
           " near " + format_length(opt) + " to solve near the optimum";
}

}  // namespace pinmask

namespace pinmask {

std::string solved_pinhole_too_large(double pinhole_m, long long pixels_per_cell) {
    if (!(pinhole_m > kMaxPinholeM)) return "";
    return "needs d = " + format_length(pinhole_m) + " for " + std::to_string(pixels_per_cell) +
           " whole pixels per cell at u, larger than any pinhole (at most " +
           format_length(kMaxPinholeM) +
           "): choose fewer pixels per cell, or optics that magnify the cells more";
}

}  // namespace pinmask
