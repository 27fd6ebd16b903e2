// Seeded planes of independent uniform values in [lo, hi) (default [0, 1)): the random inputs of
// the tests, one definition for every folder.
#pragma once

#include <cstdint>
#include <random>

#include "core/image/image.hpp"

namespace pinmask::test {

inline Plane random_plane(int rows, int cols, std::uint64_t seed, double lo = 0.0,
                          double hi = 1.0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Plane p(rows, cols);
    for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    return p;
}

}  // namespace pinmask::test
