#include "python/background_arg.hpp"

#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "decode/solvers/decode_modes.hpp"

namespace pinmask::python {

DecodeBackground background_arg(const py::handle& b) {
    if (b.is_none()) return {BackgroundMode::kNone, 0.0};
    if (py::isinstance<py::str>(b)) {
        const std::string s = b.cast<std::string>();
        for (const auto& [mode, name] : kBackgroundModeNames)
            if (mode != BackgroundMode::kValue && s == name) return {mode, 0.0};
        return {BackgroundMode::kValue, parse_number(s, field_ref("background"))};
    }
    if (py::isinstance<py::bool_>(b))
        throw invalid_field(field_ref("background"), py::str(b).cast<std::string>(),
                            "must be auto, none, corner or a number of counts");
    return {BackgroundMode::kValue, b.cast<double>()};
}

}  // namespace pinmask::python
