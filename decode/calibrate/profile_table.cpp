#include "decode/calibrate/profile_table.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "core/errors/error.hpp"
#include "core/units/number_format.hpp"
#include "design/optics/optics.hpp"
#include "design/psf/kernel_profile.hpp"

namespace pinmask::calibrate {

namespace {

// Fine-grid step of the table (pixels); the density is sampled finer when a pixel spans many
// fringes (at least 16 samples per unit v).
constexpr double kTableStep = 1.0 / 32.0;

Camera with_side(const Camera& c, double side_m) {
    Camera out = c;
    out.pinhole_m = side_m;
    return out;
}

double v_per_pixel(const Camera& c) {
    return c.pinhole_m * c.pixel_pitch_m / (c.wavelength_m * c.sensor_distance_m);
}

}  // namespace

KernelModel fit_family(const Camera& camera, KernelModel model) {
    if (model == KernelModel::kBox || model == KernelModel::kFraunhofer ||
        model == KernelModel::kFresnel)
        return model;
    return choose_kernel_model(fresnel_number_at_u(camera)).model;
}

double profile_support_px(const Camera& camera, KernelModel family, double side_m, double energy,
                          double cap_px) {
    const Camera c = with_side(camera, side_m);
    if (family == KernelModel::kBox)
        return std::min(cap_px,
                        0.5 * std::abs(magnification_at_u(c)) * side_m / c.pixel_pitch_m + 1.0);
    // sinc^2 keeps all but ~2 / (pi^2 V) beyond |v| = V; the Fresnel pattern's geometric half
    // width 2N comes first.
    const double n = family == KernelModel::kFresnel ? fresnel_number_at_u(c) : 0.0;
    const double tail = std::max(1.0 - energy, 1e-6);
    const double v = 2.0 * n + 2.0 / (std::numbers::pi * std::numbers::pi * tail);
    return std::min(cap_px, v / v_per_pixel(c) + 1.0);
}

ProfileTable::ProfileTable(const Camera& camera, KernelModel family, double side_m,
                           double half_px) {
    if (!(side_m > 0) || !std::isfinite(side_m))
        throw InvalidInput("calibrate: the fitted pinhole side " + format_number(side_m) +
                           " m is not positive");
    const Camera c = with_side(camera, side_m);
    half_ = std::max(half_px, 1.0);
    std::function<double(double)> cumulative;  // H(x), x in pixels
    std::vector<double> fine_x, fine_h;
    double fine_step = kTableStep;
    if (family == KernelModel::kBox) {
        const double w = std::abs(magnification_at_u(c)) * side_m / c.pixel_pitch_m;
        cumulative = [w](double x) {
            if (w <= 0) return x >= 0 ? 1.0 : 0.0;
            return std::clamp((x + 0.5 * w) / w, 0.0, 1.0);
        };
    } else if (family == KernelModel::kFraunhofer || family == KernelModel::kFresnel) {
        const double a = v_per_pixel(c);
        std::function<double(double)> h = fraunhofer_profile;
        if (family == KernelModel::kFresnel) {
            const FresnelProfile fp(fresnel_number_at_u(c));
            h = [fp](double v) { return fp(v); };
        }
        fine_step = std::min(kTableStep, 1.0 / (16.0 * a));
        const double reach = half_ + 0.5 + fine_step;
        const int m = static_cast<int>(std::ceil(reach / fine_step));
        fine_x.resize(2 * m + 1);
        fine_h.resize(2 * m + 1);
        for (int k = -m; k <= m; ++k) {
            fine_x[k + m] = k * fine_step;
            fine_h[k + m] = a * h(a * k * fine_step);
        }
        // Cumulative trapezoid from the left end; the energy left of it is (1 - enclosed) / 2 by
        // symmetry, added so that H is the true cumulative up to the cut tails.
        std::vector<double> cum(fine_h.size(), 0.0);
        for (std::size_t k = 1; k < cum.size(); ++k)
            cum[k] = cum[k - 1] + 0.5 * fine_step * (fine_h[k] + fine_h[k - 1]);
        const double inside = cum.back();
        const double left = 0.5 * std::max(0.0, 1.0 - inside);
        for (double& v : cum) v += left;
        const double x0 = fine_x.front();
        cumulative = [cum, x0, fine_step](double x) {
            const double t = (x - x0) / fine_step;
            if (t <= 0) return cum.front();
            if (t >= double(cum.size() - 1)) return cum.back();
            const auto k = static_cast<std::size_t>(t);
            const double f = t - double(k);
            return cum[k] + f * (cum[k + 1] - cum[k]);
        };
    } else {
        throw InvalidInput(
            "calibrate: the fit needs a kernel family with a pinhole side (box, "
            "fraunhofer or fresnel), not " +
            kernel_model_name(family));
    }
    step_ = kTableStep;
    inv_step_ = 1.0 / step_;
    const int n = static_cast<int>(std::ceil(half_ / step_));
    half_ = n * step_;
    q_.resize(2 * n + 1);
    for (int k = -n; k <= n; ++k) {
        const double x = k * step_;
        q_[k + n] = cumulative(x + 0.5) - cumulative(x - 0.5);
    }
    enclosed_ = cumulative(half_ + 0.5) - cumulative(-half_ - 0.5);
}

}  // namespace pinmask::calibrate
