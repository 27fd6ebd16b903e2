// Image type: one or more channels of row-major double arrays. Pixel (r, c) is plane(r, c);
// r is the row (y, downwards), c the column (x, rightwards). Values are linear intensities.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <cstddef>
#include <vector>

namespace pinmask {

using Plane = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using PlaneF = Eigen::Array<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ComplexPlane =
    Eigen::Array<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A multi-channel image: every channel has the same size. Grey = 1 channel, RGB = 3.
struct Image {
    std::vector<Plane> channels;

    Image() = default;
    explicit Image(Plane grey) { channels.push_back(std::move(grey)); }
    Image(int rows, int cols, int n_channels)
        : channels(static_cast<std::size_t>(n_channels), Plane::Zero(rows, cols)) {}

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
