#include "python/json_value.hpp"

namespace pinmask::python {

py::object json_value(const nlohmann::ordered_json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

}  // namespace pinmask::python
