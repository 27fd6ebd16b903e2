#include "design/psf/paper_kernel.hpp"

namespace pinmask {

const std::array<double, kPaperKernelSide * kPaperKernelSide>& paper_fig3b_table() {
    static const std::array<double, kPaperKernelSide* kPaperKernelSide> kTable = {
        0.0021, 0.0037, 0.0062, 0.0112, 0.0112, 0.0062, 0.0037, 0.0021,  //
        0.0037, 0.0074, 0.0106, 0.0204, 0.0204, 0.0106, 0.0074, 0.0037,  //
        0.0062, 0.0106, 0.0174, 0.0321, 0.0321, 0.0174, 0.0106, 0.0062,  //
        0.0112, 0.0204, 0.0321, 0.0550, 0.0550, 0.0321, 0.0204, 0.0112,  //
        0.0112, 0.0204, 0.0321, 0.0550, 0.0550, 0.0321, 0.0204, 0.0112,  //
        0.0062, 0.0106, 0.0174, 0.0321, 0.0321, 0.0174, 0.0106, 0.0062,  //
        0.0037, 0.0074, 0.0106, 0.0204, 0.0204, 0.0106, 0.0074, 0.0037,  //
        0.0021, 0.0037, 0.0062, 0.0112, 0.0112, 0.0062, 0.0037, 0.0021,  //
    };
    return kTable;
}

Plane paper_fig3b_kernel() {
    Plane k(kPaperKernelSide, kPaperKernelSide);
    const auto& t = paper_fig3b_table();
    for (int r = 0; r < kPaperKernelSide; ++r) {
        for (int c = 0; c < kPaperKernelSide; ++c) k(r, c) = t[r * kPaperKernelSide + c];
    }
    return k / k.sum();
}

}  // namespace pinmask
