// The picture depthmap writes (depthmap.png): depth in colour, by 1/u between the first and last
// plane | confidence in grey, scaled to its maximum | a colour bar from near (dark, top) to far
// (bright, bottom).
#pragma once

#include "core/image/image.hpp"
#include "decode/depthmap/depthmap.hpp"

namespace pinmask {

Image depthmap_picture(const DepthmapResult& r);

}  // namespace pinmask
