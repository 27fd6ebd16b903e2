// Which kernel model explains the measured kernel (the paper's Fig. 4 discussion): each model of
// design/psf/kernel (box, fraunhofer, fresnel, paper-fig3b) is made for the mask's camera at its
// pixels per cell, moved so its centroid sits on the measured kernel's centre (Lanczos-3),
// cropped to the measured window and normalised to sum 1 there, like the measurement. The
// residual is ||measured - model||_2 / ||measured||_2 over the window.
// A model design/ cannot make (make_kernel throws InvalidInput, e.g. paper-fig3b while its table
// is not in the repository) is listed as unavailable with design/'s reason: as soon as design/
// can make it, it is compared like the others (this list is the hook: kCompared).
#pragma once

#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "design/optics/camera.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask::calibrate {

inline constexpr KernelModel kCompared[] = {KernelModel::kBox, KernelModel::kFraunhofer,
                                            KernelModel::kFresnel, KernelModel::kPaperFig3b};

struct ModelResidual {
    std::string model;
    bool available = false;
    double residual = 0.0;  // available only
    std::string reason;     // unavailable only: design/'s message
    Plane values;           // the model on the measured window (available only)
};

// `measured` is (2 half + 1)^2 with sum 1 and its centroid at the centre pixel.
std::vector<ModelResidual> compare_kernel_models(const Plane& measured, const Camera& camera,
                                                 int pixels_per_cell);

// The available model with the smallest residual ("" when none is available).
std::string best_model(const std::vector<ModelResidual>& fits);

}  // namespace pinmask::calibrate
