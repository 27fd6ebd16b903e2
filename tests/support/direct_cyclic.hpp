// The cyclic capture written as its definition, a direct O(N^2) sum with the decoder's centring:
//     c(r, c) = sum_{i, j} a(i, j) x((r - i + ci) mod R, (c - j + cj) mod C),
// (ci, cj) = (R / 2, C / 2) the PSF's central element. The reference the FFT capture of
// optimize/simulate/simulate is tested against.
#pragma once

#include "core/image/image.hpp"

namespace pinmask::test {

inline Plane direct_cyclic(const Plane& x, const Plane& a) {
    const int R = static_cast<int>(x.rows()), C = static_cast<int>(x.cols());
    const int ci = R / 2, cj = C / 2;
    Plane out = Plane::Zero(R, C);
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c)
            for (int i = 0; i < R; ++i)
                for (int j = 0; j < C; ++j)
                    out(r, c) +=
                        a(i, j) * x(((r - i + ci) % R + R) % R, ((c - j + cj) % C + C) % C);
    return out;
}

}  // namespace pinmask::test
