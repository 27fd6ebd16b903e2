// The paper's single-pinhole kernel, its Fig. 3(b): the "synthesis diffraction pattern" of one
// 0.44 mm square pinhole behind the thin lens, sampled on the sensor's 8 x 8 pixel grid (30 um
// pixels). The 64 values are written here as printed (four decimals; they sum to 1.0012 by
// rounding) and normalised to unit sum on use. The paper's PSF of a pattern is the pattern
// upsampled by 8 with each '1' replaced by this block (paper, Sec. 2.2), so the kernel is only
// defined for 8 pixels per cell. Source of the numbers: ../shared/data/paper/fig3b-kernel.csv.
#pragma once

#include <array>

#include "core/image/image.hpp"

namespace pinmask {

// The table's side in pixels, and the only pixels-per-cell value the kernel is defined for.
inline constexpr int kPaperKernelSide = 8;

// The 64 values as printed in the paper, row-major.
const std::array<double, kPaperKernelSide * kPaperKernelSide>& paper_fig3b_table();

// The table as an 8 x 8 plane normalised to sum 1.
Plane paper_fig3b_kernel();

}  // namespace pinmask
