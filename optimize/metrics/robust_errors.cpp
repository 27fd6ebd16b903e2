#include "optimize/metrics/robust_errors.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "design/psf/kernel_quadrature.hpp"

namespace pinmask {
namespace {

std::string um_text(double metres) { return format_number(metres * 1e6) + " um"; }

// Quadrature of the jitter statistics: the Gaussian is integrated over +-kJitterRange sigma
// (the tail beyond holds 2e-19 of the mass), on panels no wider than kPanelSigmas sigma and
// never across a whole pixel (t is only piecewise smooth), with a kRulePoints-point rule.
constexpr double kJitterRange = 9.0;
constexpr double kPanelSigmas = 0.5;
constexpr int kRulePoints = 10;
// The smallest under-etched side accepted, as a fraction of d: below it the "pinhole" is a
// rounding artefact of size = d, not a hole.
constexpr double kMinSideFraction = 1e-6;

}  // namespace

void FabricationErrors::validate(double pinhole_m) const {
    const std::pair<const char*, double> all[] = {
        {"size", size_bias_m}, {"jitter", jitter_m}, {"missing", missing}};
    for (const auto& [key, v] : all) {
        if (!std::isfinite(v) || v < 0.0) {
            throw invalid_field(field_ref("robust") + " " + key, format_number(v),
                                "must be finite and >= 0");
        }
    }
    if (!(missing < 1.0)) {
        throw invalid_field(field_ref("robust") + " missing", format_number(missing),
                            "must be < 1 (the probability that a pinhole is missing; at 1 the "
                            "mask has no pinholes)");
    }
    if (pinhole_m > 0.0) {
        if (!(size_bias_m <= (1.0 - kMinSideFraction) * pinhole_m)) {
            throw invalid_field(field_ref("robust") + " size", um_text(size_bias_m),
                                "must be below the pinhole side " + um_text(pinhole_m) +
                                    " (a side d - size <= 0 leaves no hole; d - size must be at "
                                    "least 1e-6 d)");
        }
        if (!(jitter_m <= pinhole_m)) {
            throw invalid_field(field_ref("robust") + " jitter", um_text(jitter_m),
                                "must be at most one cell, the pinhole side " + um_text(pinhole_m) +
                                    " (a larger position error is not a fabrication tolerance)");
        }
    }
}

std::string FabricationErrors::description() const {
    if (!any()) return "none";
    std::ostringstream s;
    s << "size +-" << um_text(size_bias_m) << ", jitter " << um_text(jitter_m) << ", missing "
      << format_number(missing);
    return s.str();
}

FabricationErrors parse_fabrication_errors(const std::string& text) {
    if (text.empty()) {
        throw invalid_field(field_ref("robust"), "''",
                            "expected key=value items separated by commas: size=5um, jitter=2um, "
                            "missing=0.01");
    }
    FabricationErrors e;
    std::set<std::string> seen;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos) {
            throw invalid_field(field_ref("robust"), "'" + item + "'",
                                "each item must be key=value with key size, jitter or missing");
        }
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        const std::string field = field_ref("robust") + " " + key;
        if (key != "size" && key != "jitter" && key != "missing") {
            throw invalid_field(field_ref("robust"), "'" + key + "'",
                                "unknown key: expected size, jitter or missing");
        }
        if (!seen.insert(key).second) {
            throw invalid_field(field, "'" + text + "'", "the key is given twice");
        }
        if (key == "size") e.size_bias_m = parse_length_m(value, field);
        if (key == "jitter") e.jitter_m = parse_length_m(value, field);
        if (key == "missing") e.missing = parse_number(value, field);
    }
    if (!text.empty() && text.back() == ',') {
        throw invalid_field(field_ref("robust"), "'" + text + "'", "ends with an empty item");
    }
    e.validate();
    return e;
}

JitterTransfer jitter_transfer(double sigma_px, int m) {
    if (!std::isfinite(sigma_px) || sigma_px < 0.0) {
        throw invalid_field("jitter sigma (pixels)", format_number(sigma_px),
                            "must be finite and >= 0");
    }
    if (m < 1) throw invalid_field("jitter period", std::to_string(m), "must be >= 1");
    JitterTransfer out;
    out.mean.assign(static_cast<std::size_t>(m), 1.0);
    out.power.assign(static_cast<std::size_t>(m), 1.0);
    if (sigma_px == 0.0) return out;

    // Nodes (delta, weight) of E[.] over N(0, sigma^2): panels between the breakpoints (whole
    // pixels and the range ends), each split to at most kPanelSigmas sigma wide.
    const GaussLegendreRule rule = gauss_legendre(kRulePoints);
    const double lo = -kJitterRange * sigma_px, hi = kJitterRange * sigma_px;
    std::vector<double> breaks{lo};
    for (double b = std::floor(lo) + 1.0; b < hi; b += 1.0) breaks.push_back(b);
    breaks.push_back(hi);
    std::vector<double> delta, weight;
    double total = 0.0;
    for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
        const double a = breaks[p], b = breaks[p + 1];
        const int panels =
            std::max(1, static_cast<int>(std::ceil((b - a) / (kPanelSigmas * sigma_px))));
        const double h = (b - a) / panels;
        for (int q = 0; q < panels; ++q) {
            const double mid = a + (q + 0.5) * h;
            for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
                const double x = mid + 0.5 * h * rule.nodes[i];
                const double w =
                    0.5 * h * rule.weights[i] * std::exp(-0.5 * (x / sigma_px) * (x / sigma_px));
                delta.push_back(x);
                weight.push_back(w);
                total += w;
            }
        }
    }
    const double two_pi = 2.0 * std::acos(-1.0);
    for (int k = 0; k < m; ++k) {
        const double theta = two_pi * k / m;
        std::complex<double> mean = 0.0;
        double power = 0.0;
        for (std::size_t i = 0; i < delta.size(); ++i) {
            const double s = std::floor(delta[i]), f = delta[i] - s;
            const std::complex<double> t =
                std::polar(1.0, -theta * s) * ((1.0 - f) + f * std::polar(1.0, -theta));
            mean += weight[i] * t;
            power +=
                weight[i] * ((1.0 - f) * (1.0 - f) + f * f + 2.0 * f * (1.0 - f) * std::cos(theta));
        }
        out.mean[static_cast<std::size_t>(k)] = mean / total;
        out.power[static_cast<std::size_t>(k)] = power / total;
    }
    return out;
}

}  // namespace pinmask
