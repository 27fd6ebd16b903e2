#include "core/errors/error.hpp"

#include "core/units/units.hpp"

namespace pinmask {

InvalidInput invalid_field(const std::string& field, const std::string& value,
                           const std::string& rule) {
    // Numbers spelled out by std::to_string (301 digits for 1e300) are shown as %g.
    return InvalidInput(field + " = " + readable_numbers(value) + ": " + readable_numbers(rule));
}

}  // namespace pinmask
