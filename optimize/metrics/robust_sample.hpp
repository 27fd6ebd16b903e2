// The fabricated pinhole of the error model (optimize/metrics/robust_errors.hpp) as design/psf/psf
// kernels, and the jitter in sensor pixels: what the closed-form robust figure
// (optimize/metrics/robust_wiener) is built from. (The Monte-Carlo sample of whole fabricated masks
// the closed form is tested against is test code: tests/research/fabricated_sample.hpp.)
#pragma once

#include <vector>

#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"
#include "optimize/metrics/robust_errors.hpp"

namespace pinmask {

// The kernels of a fabricated pinhole: {d + b, d - b} for a size bias b > 0, else {d}, each
// design/psf/psf's mask_kernel for the mask with that pinhole side. Validates the errors against
// the mask (InvalidInput naming --robust and the key); a size bias with a kernel that does not
// depend on the pinhole side (paper-fig3b, measured) is InvalidInput naming --robust size.
std::vector<Kernel> fabricated_kernels(const Mask& mask, const FabricationErrors& errors,
                                       const KernelOptions& options = {});

// Jitter sigma in sensor pixels: sigma_m ppc / d (one cell is d on the mask, ppc pixels).
double jitter_sigma_px(const Mask& mask, const FabricationErrors& errors);

}  // namespace pinmask
