// The background= keyword of decode() and depthmap(), as their commands' --background takes it:
// None or "none", "auto", "corner", or a number of counts (or its text). The library says which
// modes each pipeline accepts.
#pragma once

#include "decode/capture/decode_request.hpp"
#include "python/common.hpp"

namespace pinmask::python {

DecodeBackground background_arg(const py::handle& background);

}  // namespace pinmask::python
