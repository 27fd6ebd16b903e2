#include "core/image.hpp"

namespace pinmask {

std::shared_ptr<const MemoryReservation> charge_image_memory(double bytes, const char* what) {
    if (bytes < kChargeThresholdBytes) return nullptr;
    return std::make_shared<const MemoryReservation>(bytes, what);
}

bool is_all_finite(const Plane& p) { return p.isFinite().all(); }

Plane circshift(const Plane& in, int dr, int dc) {
    const Eigen::Index rows = in.rows(), cols = in.cols();
    Plane out(rows, cols);
    if (rows == 0 || cols == 0) return out;
    const Eigen::Index sr = ((dr % rows) + rows) % rows;
    const Eigen::Index sc = ((dc % cols) + cols) % cols;
    for (Eigen::Index r = 0; r < rows; ++r) {
        const Eigen::Index rr = (r + sr) % rows;
        for (Eigen::Index c = 0; c < cols; ++c) out(rr, (c + sc) % cols) = in(r, c);
    }
    return out;
}

}  // namespace pinmask
