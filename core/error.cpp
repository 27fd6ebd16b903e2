#include "core/error.hpp"

namespace pinmask {

InvalidInput invalid_field(const std::string& field, const std::string& value,
                           const std::string& rule) {
    return InvalidInput(field + " = " + value + ": " + rule);
}

}  // namespace pinmask
