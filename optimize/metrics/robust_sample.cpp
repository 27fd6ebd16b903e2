#include "optimize/metrics/robust_sample.hpp"

#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/psf/psf.hpp"

namespace pinmask {

std::vector<Kernel> fabricated_kernels(const Mask& mask, const FabricationErrors& errors,
                                       const KernelOptions& options) {
    errors.validate(mask.camera.pinhole_m);
    if (!(errors.size_bias_m > 0.0)) return {mask_kernel(mask, options)};
    std::vector<Kernel> out;
    for (const double sign : {1.0, -1.0}) {
        Mask m = mask;
        m.camera.pinhole_m = mask.camera.pinhole_m + sign * errors.size_bias_m;
        out.push_back(mask_kernel(m, options));
    }
    const KernelModel model = out.front().model;
    if (model == KernelModel::kPaperFig3b || model == KernelModel::kMeasured) {
        throw invalid_field(field_ref("robust") + " size",
                            std::to_string(errors.size_bias_m * 1e6) + " um",
                            "needs a kernel model that depends on the pinhole side (box, "
                            "fraunhofer, fresnel, auto); the mask's kernel is " +
                                kernel_model_name(model));
    }
    return out;
}

double jitter_sigma_px(const Mask& mask, const FabricationErrors& errors) {
    return errors.jitter_m / mask.camera.pinhole_m * mask.psf.pixels_per_cell;
}

}  // namespace pinmask
