// Names of the single-pinhole kernel models and the rule "auto" follows. Notation as in
// design/psf/kernel_profile.hpp (N = Fresnel number with the lens at the object distance u).
#pragma once

#include <string>
#include <string_view>

#include "core/errors/name_table.hpp"

namespace pinmask {

enum class KernelModel {
    kAuto,        // pick box / fraunhofer / fresnel from N (choose_kernel_model)
    kBox,         // geometric spot: a square of side |M| d, exact pixel overlaps
    kFraunhofer,  // sinc^2(d x / (lambda f)) per axis (the N = 0 limit)
    kFresnel,     // the full Fresnel pattern with the lens phase (any N)
    kPaperFig3b,  // the paper's measured 8 x 8 kernel table (design/psf/paper_kernel.hpp), 8
                  // px/cell
    kMeasured,    // a kernel image file
};

// The one table of the models' names: the flags' and keywords' values, the help texts, the mask
// file's "kernel.model" and the reports all read it (core/errors/name_table.hpp: names_of,
// name_list).
inline constexpr NameTable<KernelModel, 6> kKernelModelNames{{
    {KernelModel::kAuto, "auto"},
    {KernelModel::kBox, "box"},
    {KernelModel::kFraunhofer, "fraunhofer"},
    {KernelModel::kFresnel, "fresnel"},
    {KernelModel::kPaperFig3b, "paper-fig3b"},
    {KernelModel::kMeasured, "measured"},
}};

// A name of kKernelModelNames. Throws InvalidInput naming `field`, the value and the list
// otherwise.
KernelModel parse_kernel_model(std::string_view name, std::string_view field = "kernel model");
std::string kernel_model_name(KernelModel model);
// The names joined by " | " ("auto | box | ..."), for help texts.
std::string kernel_model_names();

// "auto" aims at an L1 distance of at most kAutoL1Target between the chosen model's continuous
// 1-D profile and the Fresnel profile (int |h_model - h_fresnel| dv; both integrate to 1):
//   N <= kAutoFraunhoferMaxN -> fraunhofer (L1 = 0.0196 at the bound, growing as N^2),
//   N >= kAutoBoxMinN        -> box        (L1 = 0.0189 at the bound, falling as ~N^-0.4: the
//                                             edge fringes and the diffracted tails),
//   otherwise                -> fresnel.
// Measured by tests/design/test_kernel_model.cpp, which checks both bounds.
inline constexpr double kAutoL1Target = 0.02;
inline constexpr double kAutoFraunhoferMaxN = 0.125;
inline constexpr double kAutoBoxMinN = 5000.0;

struct KernelChoice {
    KernelModel model = KernelModel::kFresnel;
    std::string reason;  // one sentence for reports, e.g. "N = 0.88 is between 0.125 and 5000"
};

// The model auto picks for Fresnel number N (sign ignored). Throws InvalidInput for NaN.
KernelChoice choose_kernel_model(double fresnel_number);

}  // namespace pinmask
