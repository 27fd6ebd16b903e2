#include "design/psf/kernel_validity.hpp"

#include <cmath>
#include <cstdio>

#include "core/errors/field_names.hpp"
#include "design/optics/optics.hpp"

namespace pinmask {
namespace {

std::string g(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace

KernelValidity kernel_validity(const Camera& camera, KernelModel model, double energy_kept) {
    KernelValidity v;
    v.fresnel_number = std::fabs(fresnel_number_at_u(camera));
    v.magnification = magnification_at_u(camera);
    const double n = v.fresnel_number;
    v.model = model == KernelModel::kAuto && !std::isnan(n) ? choose_kernel_model(n).model : model;

    const double waves = camera.pinhole_m / camera.wavelength_m;
    if (!(waves >= kMinApertureWavelengths)) {
        v.model_accurate = false;
        v.warnings.push_back(
            "the pinhole is " + g(waves) + " wavelengths wide (d = " + g(camera.pinhole_m) +
            " m, lambda = " + g(camera.wavelength_m) +
            " m): every kernel model assumes scalar paraxial diffraction, "
            "which needs at least " +
            g(kMinApertureWavelengths) + " wavelengths; no model is accurate here");
    }
    if (!std::isfinite(n)) {
        v.model_accurate = false;
        v.warnings.push_back("the Fresnel number is " + g(n) +
                             ": no kernel model is defined there (sensor at the lens?)");
    } else if (v.model == KernelModel::kFraunhofer && n > kAutoFraunhoferMaxN) {
        v.model_accurate = false;
        v.warnings.push_back("fraunhofer (sinc^2) is used at N = " + g(n) +
                             ", outside its accurate range N <= " + g(kAutoFraunhoferMaxN) +
                             " (L1 error > " + g(kAutoL1Target) + "); use fresnel");
    } else if (v.model == KernelModel::kBox && n < kAutoBoxMinN) {
        v.model_accurate = false;
        v.warnings.push_back("box (geometric) is used at N = " + g(n) +
                             ", outside its accurate range N >= " + g(kAutoBoxMinN) +
                             " (L1 error > " + g(kAutoL1Target) + "); use fresnel");
    }
    if (!std::isfinite(v.magnification) || v.magnification == 0.0) {
        v.warnings.push_back("the magnification M = 1 - f/f' + f/u is " + g(v.magnification) +
                             ": all pinhole images fall on one spot (f = f' images the pattern "
                             "at a single point), the mask is not imaged");
    }
    if (!(1.0 - energy_kept <= kMaxKernelEnergyLoss)) {
        v.energy_ok = false;
        v.warnings.push_back(
            "the kernel's support keeps " + g(100.0 * energy_kept) +
            " % of its energy (loses more than " + g(100.0 * kMaxKernelEnergyLoss) +
            " %); the kept part is renormalised, so the PSF misstates the "
            "spread: raise " +
            field_ref("energy_fraction") + ", or the period (grid x pixels per cell)");
    }
    return v;
}

}  // namespace pinmask
