#include "design/psf/design_kernel.hpp"

#include "core/errors/error.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/psf.hpp"

namespace pinmask {

DesignKernel design_kernel(const Camera& camera, int n, int ppc, const std::string& model) {
    DesignKernel out;
    const KernelModel requested = parse_kernel_model(model, "kernel model");
    if (requested == KernelModel::kMeasured) {
        out.not_built = "a measured kernel is an image, and design has none";
    } else {
        Mask m;
        m.camera = camera;
        m.pattern.n = n;
        m.psf.pixels_per_cell = ppc;
        m.psf.kernel.model = model;
        try {
            out.kernel = mask_kernel(m);
        } catch (const InvalidInput& e) {
            out.not_built = e.what();
        }
    }
    const KernelModel resolved = out.kernel ? out.kernel->model : requested;
    out.validity =
        kernel_validity(camera, resolved, out.kernel ? out.kernel->enclosed_energy : 1.0);
    if (!out.kernel && requested != KernelModel::kMeasured) {
        out.validity.warnings.push_back(
            "the kernel was not built, so its support and energy "
            "are unchecked: " +
            out.not_built);
    }
    return out;
}

}  // namespace pinmask
