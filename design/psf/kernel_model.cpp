#include "design/psf/kernel_model.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

}  // namespace

KernelModel parse_kernel_model(std::string_view name, std::string_view field) {
    std::string list;
    for (const auto& [model, text] : kKernelModelNames) {
        if (name == text) return model;
        list += (list.empty() ? "" : ", ") + std::string(text);
    }
    throw invalid_field(std::string(field), "'" + std::string(name) + "'",
                        "must be one of " + list);
}

std::string kernel_model_name(KernelModel model) {
    for (const auto& [m, text] : kKernelModelNames) {
        if (m == model) return text;
    }
    return "unknown";
}

std::string kernel_model_names() { return names_of(kKernelModelNames); }

KernelChoice choose_kernel_model(double fresnel_number) {
    if (std::isnan(fresnel_number)) {
        throw invalid_field("fresnel_number", "nan", "must be a number");
    }
    // N = d^2 |1/f - 1/f' + 1/u| / (4 lambda) is never negative: a negative value is a wrong
    // input, not a distance on the other side of focus (every caller passes the magnitude).
    if (fresnel_number < 0.0) {
        throw invalid_field("fresnel_number", number(fresnel_number),
                            "must be >= 0 (N = d^2 |1/f - 1/f' + 1/u| / (4 lambda))");
    }
    const double n = fresnel_number;
    const std::string l1 = " (L1 error <= " + number(kAutoL1Target) + ")";
    if (n <= kAutoFraunhoferMaxN) {
        return {KernelModel::kFraunhofer, "N = " + number(n) +
                                              " <= " + number(kAutoFraunhoferMaxN) +
                                              ": far field, sinc^2 is accurate" + l1};
    }
    if (n >= kAutoBoxMinN) {
        return {KernelModel::kBox, "N = " + number(n) + " >= " + number(kAutoBoxMinN) +
                                       ": geometric spot, the box is accurate" + l1};
    }
    return {KernelModel::kFresnel,
            "N = " + number(n) + " is between " + number(kAutoFraunhoferMaxN) + " and " +
                number(kAutoBoxMinN) + ": neither limit is accurate, full Fresnel pattern"};
}

}  // namespace pinmask
