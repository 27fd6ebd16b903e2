// Image type: one or more channels of row-major double arrays. Pixel (r, c) is plane(r, c);
// r is the row (y, downwards), c the column (x, rightwards). Values are linear intensities.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/limits/resource_limits.hpp"

namespace pinmask {

using Plane = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using PlaneF = Eigen::Array<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ComplexPlane =
    Eigen::Array<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Charge for `bytes` of image data against the process-wide budget (core/limits/resource_limits),
// or none below kChargeThresholdBytes. Throws ResourceLimit naming `what`.
std::shared_ptr<const MemoryReservation> charge_image_memory(double bytes, const char* what);

// A multi-channel image: every channel has the same size. Grey = 1 channel, RGB = 3.
// `charge` holds the memory budget of large images (made by the sized constructor or by the
// image readers) for as long as any copy of the image lives.
struct Image {
    std::shared_ptr<const MemoryReservation> charge;
    std::vector<Plane> channels;

    Image() = default;
    explicit Image(Plane grey) { channels.push_back(std::move(grey)); }
    Image(int rows, int cols, int n_channels)
        : charge(charge_image_memory(8.0 * rows * cols * n_channels, "an image")),
          channels(static_cast<std::size_t>(n_channels), Plane::Zero(rows, cols)) {}

    int rows() const { return channels.empty() ? 0 : static_cast<int>(channels[0].rows()); }
    int cols() const { return channels.empty() ? 0 : static_cast<int>(channels[0].cols()); }
    int n_channels() const { return static_cast<int>(channels.size()); }
    bool empty() const { return channels.empty() || rows() == 0 || cols() == 0; }
};

// True when every value of the plane is finite (no NaN, no Inf).
bool is_all_finite(const Plane& p);

// Circular shift: out(r, c) = in((r - dr) mod rows, (c - dc) mod cols).
Plane circshift(const Plane& in, int dr, int dc);

}  // namespace pinmask
