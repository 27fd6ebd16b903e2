// Is a kernel model accurate for this camera, and how much of the kernel's energy did the kept
// support lose? A query, asked by psf and design before they label a result "accurate", and by
// tests (tests/design/test_extreme_physics.cpp). Every model assumes scalar paraxial
// diffraction; beyond that each has its own Fresnel-number range (design/psf/kernel_model.hpp):
//   - scalar diffraction: the pinhole must be at least kMinApertureWavelengths wavelengths wide
//     (a 1e300 m wavelength is not "the far field", it is outside every model);
//   - fraunhofer (sinc^2): N <= kAutoFraunhoferMaxN; box: N >= kAutoBoxMinN; fresnel: any
//     finite N; measured: whatever it measured (no range to check);
//   - energy: a kernel whose support kept less than 1 - kMaxKernelEnergyLoss of its energy is
//     renormalised from a truncated pattern: warned;
//   - magnification M = 0 (f = f' with u = inf, or u -> f f'/(f - f')): every pinhole image
//     lands on the same spot, the pattern is not imaged (warned, not refused).
#pragma once

#include <string>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask {

inline constexpr double kMinApertureWavelengths = 10.0;
inline constexpr double kMaxKernelEnergyLoss = 0.01;

struct KernelValidity {
    double fresnel_number = 0;  // N(u) = d^2 |1/z_eff(u)| / (4 lambda), design/optics/optics
    double magnification = 0;   // M(u)
    KernelModel model = KernelModel::kFresnel;  // as asked (kAuto resolved)
    bool model_accurate = true;  // the model is accurate at this N and the optics are scalar
    bool energy_ok = true;       // 1 - energy_kept <= kMaxKernelEnergyLoss
    // One sentence each, naming the figure and the rule; settings as field_ref (the faces spell).
    std::vector<std::string> warnings;
    bool ok() const { return warnings.empty(); }
};

// `energy_kept` = Kernel::enclosed_energy (1 when no kernel was built). Never throws for finite
// or infinite cameras that passed validate(Camera); NaN figures become a warning.
KernelValidity kernel_validity(const Camera& camera, KernelModel model, double energy_kept = 1.0);

}  // namespace pinmask
