// Seeded planes of independent uniform values in [lo, hi): the random inputs of the tests (each
// test file names its range once, in a one-line random_plane of its own).
#pragma once

#include <cstdint>
#include <random>

#include "core/image.hpp"

namespace pinmask::test {

inline Plane uniform_plane(int rows, int cols, std::uint64_t seed, double lo, double hi) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Plane p(rows, cols);
    for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    return p;
}

}  // namespace pinmask::test
