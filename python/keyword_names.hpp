// Python's spelling of the libraries' settings fields: the one table that maps a field name a
// library uses in its messages (core/errors/field_names.hpp) to the keyword argument that sets it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace pinmask::py_names {

// "iters" for "iterations", ...; a field without a row in the table is its own keyword.
std::optional<std::string> keyword_spelling(std::string_view field);

// `message` as Python says it: every field reference spelled as its keyword.
std::string spell_keywords(std::string_view message);

}  // namespace pinmask::py_names
