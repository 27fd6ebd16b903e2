// A JSON value the library's io/ rendered, as the Python value json.loads gives (objects as
// dicts in the same key order, null as None), so a function's result is the command's --json.
#pragma once

#include <nlohmann/json.hpp>

#include "python/common.hpp"

namespace pinmask::python {

py::object json_value(const nlohmann::ordered_json& j);

}  // namespace pinmask::python
