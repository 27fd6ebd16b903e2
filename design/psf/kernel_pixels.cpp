// Pixel integration of the 1-D profiles (contract in design/psf/kernel.hpp).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_quadrature.hpp"

namespace pinmask {
namespace {

// Panel width in v: the profile is band-limited to 1 cycle per unit v, so a 12-point rule on
// half a cycle is exact to rounding (error term ~ (pi/2)^24 / 24! ~ 1e-19).
constexpr double kPanelV = 0.5;
constexpr int kPanelPoints = 12;
// Work bound for one profile: pixels x panels per pixel x points.
constexpr double kMaxEvaluations = 5e7;

void check_ppc(int ppc) {
    if (ppc < 1 || ppc > kMaxPixelsPerCell) {
        throw invalid_field("pixels_per_cell", std::to_string(ppc),
                            "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
    }
}

}  // namespace

void validate(const KernelOptions& o) {
    if (!(o.energy_fraction > 0.0 && o.energy_fraction <= 1.0)) {
        throw invalid_field("energy_fraction", std::to_string(o.energy_fraction),
                            "must be in (0, 1]");
    }
    if (o.max_width_px < 1) {
        throw invalid_field("max_width_px", std::to_string(o.max_width_px), "must be >= 1");
    }
}

PixelProfile box_pixel_profile(double spot_px, int ppc, const KernelOptions& options) {
    check_ppc(ppc);
    validate(options);
    if (!(spot_px >= 0.0) || std::isinf(spot_px)) {
        throw invalid_field("geometric spot (pixels)", std::to_string(spot_px),
                            "must be finite and >= 0");
    }
    PixelProfile p;
    if (spot_px == 0.0) {  // a point: split over the pixels that share the centre
        p.origin = ppc % 2 == 0 ? ppc / 2 - 1 : ppc / 2;
        p.values = ppc % 2 == 0 ? std::vector<double>{0.5, 0.5} : std::vector<double>{1.0};
        return p;
    }
    // Right half relative to the centre (mirrored, so the profile is exactly symmetric): pixel k
    // covers [a0 + k, a0 + k + 1] with a0 = 1/2 for odd ppc (whose central pixel is [-1/2, 1/2]).
    const bool odd = ppc % 2 == 1;
    const double half = 0.5 * spot_px, a0 = odd ? 0.5 : 0.0;
    const int centre_pixels = odd ? 1 : 0;
    const double centre = odd ? 2.0 * std::min(half, 0.5) / spot_px : 0.0;
    const double full_pairs = std::max(0.0, std::ceil(half - a0));
    const double cap_pairs = std::floor((options.max_width_px - centre_pixels) / 2.0);
    const int pairs = static_cast<int>(std::max(odd ? 0.0 : 1.0, std::min(full_pairs, cap_pairs)));
    p.capped = pairs < full_pairs;
    p.origin = ppc / 2 - pairs;
    p.values.assign(static_cast<std::size_t>(2 * pairs + centre_pixels), 0.0);
    double kept = centre;
    if (odd) p.values[pairs] = centre;
    for (int k = 0; k < pairs; ++k) {
        const double e = std::clamp(half - (a0 + k), 0.0, 1.0) / spot_px;
        p.values[pairs + centre_pixels + k] = e;
        p.values[pairs - 1 - k] = e;
        kept += 2.0 * e;
    }
    p.enclosed = std::min(1.0, kept);
    return p;
}

PixelProfile box_pixel_profile_at(double spot_px, double centre, const KernelOptions& options) {
    validate(options);
    if (!(spot_px >= 0.0) || std::isinf(spot_px)) {
        throw invalid_field("geometric spot (pixels)", std::to_string(spot_px),
                            "must be finite and >= 0");
    }
    if (!std::isfinite(centre) || std::fabs(centre) > 1e9) {
        throw invalid_field("spot centre (pixels)", std::to_string(centre),
                            "must be finite and within 1e9 pixels");
    }
    PixelProfile p;
    const double half = 0.5 * spot_px;
    if (spot_px == 0.0) {  // a point: its pixel, or split evenly over the two sharing an edge
        const double f = std::floor(centre);
        p.origin = static_cast<int>(f) - (f == centre ? 1 : 0);
        p.values = f == centre ? std::vector<double>{0.5, 0.5} : std::vector<double>{1.0};
        return p;
    }
    long long lo = static_cast<long long>(std::floor(centre - half));
    long long hi = static_cast<long long>(std::ceil(centre + half));  // exclusive
    if (hi <= lo) hi = lo + 1;
    if (hi - lo > options.max_width_px) {
        lo = static_cast<long long>(std::floor(centre)) - (options.max_width_px - 1) / 2;
        hi = lo + options.max_width_px;
        p.capped = true;
    }
    p.origin = static_cast<int>(lo);
    p.values.assign(static_cast<std::size_t>(hi - lo), 0.0);
    double kept = 0.0;
    for (long long k = lo; k < hi; ++k) {
        const double a = std::max(static_cast<double>(k), centre - half);
        const double b = std::min(static_cast<double>(k + 1), centre + half);
        const double e = std::max(0.0, b - a) / spot_px;
        p.values[static_cast<std::size_t>(k - lo)] = e;
        kept += e;
    }
    p.enclosed = std::min(1.0, kept);
    return p;
}

PixelProfile diffraction_pixel_profile(const std::function<double(double)>& h, double pixel_v,
                                       int ppc, const KernelOptions& options) {
    check_ppc(ppc);
    validate(options);
    if (!(pixel_v > 0.0) || std::isinf(pixel_v)) {
        throw invalid_field("pixel width in v = d w / (lambda f)", std::to_string(pixel_v),
                            "must be finite and > 0");
    }
    static const GaussLegendreRule rule = gauss_legendre(kPanelPoints);
    const double panels_d = std::ceil(pixel_v / kPanelV);
    const auto too_much = [&] {
        return invalid_field("pixel width in v = d w / (lambda f)", std::to_string(pixel_v),
                             "the pixels span too many diffraction fringes to integrate (more "
                             "than " +
                                 std::to_string(static_cast<long long>(kMaxEvaluations)) +
                                 " evaluations; wavelength far below the pixel scale or a huge "
                                 "spot); use the box model");
    };
    if (panels_d * kPanelPoints * 4 > kMaxEvaluations) throw too_much();
    const int panels = static_cast<int>(panels_d);
    const bool odd = ppc % 2 == 1;
    // Right half: pixel k covers v in [a0 + k pixel_v, a0 + (k + 1) pixel_v]; for odd ppc the
    // central pixel covers [-a0, a0].
    const double a0 = odd ? 0.5 * pixel_v : 0.0;
    const double centre = odd ? 2.0 * integrate_panels(rule, 0.0, a0, (panels + 1) / 2, h) : 0.0;
    double energy = centre, evaluations = panels * kPanelPoints;
    std::vector<double> right;
    bool capped = false;
    const int centre_pixels = odd ? 1 : 0;
    const std::size_t min_pairs = odd ? 0 : 1;  // even ppc: at least the two central pixels
    while (right.size() < min_pairs || energy < options.energy_fraction) {
        const int width_next = centre_pixels + 2 * static_cast<int>(right.size() + 1);
        if (width_next > options.max_width_px && right.size() >= min_pairs) {
            capped = true;
            break;
        }
        evaluations += panels * kPanelPoints;
        if (evaluations > kMaxEvaluations) throw too_much();
        const double a = a0 + static_cast<double>(right.size()) * pixel_v;
        const double e = integrate_panels(rule, a, a + pixel_v, panels, h);
        right.push_back(e);
        energy += 2.0 * e;
    }
    PixelProfile p;
    p.capped = capped;
    p.enclosed = std::min(1.0, energy);
    const int half = static_cast<int>(right.size());
    // Odd ppc: pixel ppc/2 (rounded down) holds the centre; even: the centre is the corner
    // between pixels ppc/2 - 1 and ppc/2.
    p.origin = ppc / 2 - half;
    p.values.assign(static_cast<std::size_t>(2 * half + centre_pixels), 0.0);
    if (odd) p.values[half] = centre;
    for (int k = 0; k < half; ++k) {
        p.values[half + centre_pixels + k] = right[k];
        p.values[half - 1 - k] = right[k];
    }
    return p;
}

}  // namespace pinmask
