#include "decode/calibrate/kernel_fit.hpp"

#include "core/errors/error.hpp"
#include "decode/calibrate/subpixel.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask::calibrate {

std::vector<ModelResidual> compare_kernel_models(const Plane& measured, const Camera& camera,
                                                 int pixels_per_cell) {
    const int size = static_cast<int>(measured.rows());
    const int half = size / 2;
    std::vector<ModelResidual> out;
    for (const KernelModel model : kCompared) {
        const std::string name = kernel_model_name(model);
        ModelResidual m;
        m.model = name;
        try {
            KernelSpec spec;
            spec.model = name;
            KernelOptions ko;
            ko.max_width_px = size + 2 * kLanczosA + 2;  // the window plus the interpolation taps
            const Kernel k = make_kernel(camera, spec, pixels_per_cell, ko);
            double ky = 0, kx = 0;
            centroid(k.values, ky, kx);
            Plane w = Plane::Zero(size, size);
            add_kernel(w, k.values, ky, kx, half, half, 1.0);
            const double s = w.sum();
            if (!(s > 0.0)) throw InvalidInput("the model has no energy in the measured window");
            m.values = w / s;
            m.available = true;
            m.residual = (measured - m.values).matrix().norm() / measured.matrix().norm();
        } catch (const InvalidInput& e) {
            m.reason = e.what();
        }
        out.push_back(std::move(m));
    }
    return out;
}

std::string best_model(const std::vector<ModelResidual>& fits) {
    std::string best;
    double r = 0.0;
    for (const auto& f : fits)
        if (f.available && (best.empty() || f.residual < r)) {
            best = f.model;
            r = f.residual;
        }
    return best;
}

}  // namespace pinmask::calibrate
