#include "decode/capture/preprocess.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

double patch_mean(const Plane& p, int row0, int col0, int size) {
    if (size < 1 || row0 < 0 || col0 < 0 || row0 + size > p.rows() || col0 + size > p.cols()) {
        throw InvalidInput("background patch: " + std::to_string(size) + " x " +
                           std::to_string(size) + " at (row " + std::to_string(row0) + ", col " +
                           std::to_string(col0) + ") does not fit in a plane of " +
                           std::to_string(p.cols()) + " x " + std::to_string(p.rows()) +
                           " (W x H): the patch must lie inside the PSF");
    }
    return p.block(row0, col0, size, size).mean();
}

double corner_background(const Plane& p) {
    return patch_mean(p, kCornerPatchStart, kCornerPatchStart, kCornerPatchSize);
}

Plane box_downsample_2x(const Plane& p) {
    const Eigen::Index rows = p.rows() / 2, cols = p.cols() / 2;
    if (rows < 1 || cols < 1) {
        throw InvalidInput("downsample: a plane of " + std::to_string(p.cols()) + " x " +
                           std::to_string(p.rows()) +
                           " (W x H) cannot be 2 x 2 box-averaged: both sides must be >= 2");
    }
    Plane out(rows, cols);
    for (Eigen::Index r = 0; r < rows; ++r)
        for (Eigen::Index c = 0; c < cols; ++c)
            out(r, c) = 0.25 * (p(2 * r, 2 * c) + p(2 * r, 2 * c + 1) + p(2 * r + 1, 2 * c) +
                                p(2 * r + 1, 2 * c + 1));
    return out;
}

Plane box_downsample(const Plane& p, int rounds) {
    if (rounds < 0) {
        throw invalid_field("downsample rounds", std::to_string(rounds), "must be >= 0");
    }
    Plane out = p;
    for (int k = 0; k < rounds; ++k) out = box_downsample_2x(out);
    return out;
}

namespace {

double positive_factor(double v, const char* what, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) {
        throw InvalidInput(std::string(what) + ": " + name + " is " + std::to_string(v) +
                           ": normalisation needs a finite, non-zero image");
    }
    return v;
}

}  // namespace

double channels_l2_norm(const std::vector<Plane>& channels, const char* what) {
    double squares = 0.0;
    for (const Plane& p : channels) squares += p.matrix().squaredNorm();
    return positive_factor(std::sqrt(squares / static_cast<double>(channels.size())), what,
                           "L2 norm");
}

double channels_mean_sum(const std::vector<Plane>& channels, const char* what) {
    double sum = 0.0;
    for (const Plane& p : channels) sum += p.sum();
    return positive_factor(sum / static_cast<double>(channels.size()), what, "sum");
}

}  // namespace pinmask
