#include "calibrate/kernel_estimate.hpp"

#include "calibrate/spots.hpp"
#include "calibrate/subpixel.hpp"
#include "core/error.hpp"

namespace pinmask::calibrate {

KernelEstimate estimate_kernel(const Plane& frame, const std::vector<Eigen::Vector2d>& centres,
                               const std::vector<double>& fluxes, int half) {
    if (centres.empty() || centres.size() != fluxes.size())
        throw InvalidInput("calibrate: no usable spot to estimate the kernel from");
    const int size = 2 * half + 1;
    std::vector<Plane> windows;
    windows.reserve(centres.size());
    for (std::size_t k = 0; k < centres.size(); ++k)
        windows.push_back(sample_window(frame, centres[k].y(), centres[k].x(), half) / fluxes[k]);
    KernelEstimate e;
    e.half_px = half;
    e.spots_used = static_cast<int>(windows.size());
    e.values = Plane::Zero(size, size);
    std::vector<double> v(windows.size());
    for (int r = 0; r < size; ++r)
        for (int c = 0; c < size; ++c) {
            for (std::size_t k = 0; k < windows.size(); ++k) v[k] = windows[k](r, c);
            e.values(r, c) = median_of(v);
        }
    const double s = e.values.sum();
    if (!(s > 0.0)) throw InvalidInput("calibrate: the averaged kernel has no positive sum");
    e.values /= s;
    return e;
}

}  // namespace pinmask::calibrate
