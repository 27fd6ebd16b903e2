// The kernel a design's mask would get, built at design time so `design` (and Python optics())
// report its band and warn about it exactly as `psf` does for the mask: the camera's spectrum
// (design/optics/spectrum), the model resolved over every sampled wavelength, and the energy its
// support keeps on the period of n N pixels (design/psf/psf mask_kernel, the kernel psf builds).
#pragma once

#include <optional>
#include <string>

#include "design/optics/camera.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_validity.hpp"

namespace pinmask {

struct DesignKernel {
    std::optional<Kernel> kernel;  // empty when it cannot be built (see not_built)
    std::string not_built;         // why not (a measured model has no file here; an error's text)
    KernelValidity validity;       // with the kernel's kept energy; warns when not built
};

// `model` as KernelSpec::model; n cells per side, ppc whole pixels per cell at u. Never throws
// for a camera that passed validate(Camera): a kernel that cannot be built is a warning.
DesignKernel design_kernel(const Camera& camera, int n, int ppc, const std::string& model);

}  // namespace pinmask
