// The command line's spelling of the libraries' settings fields: the one table that maps a field
// name a library uses in its messages (core/errors/field_names.hpp) to the flag that sets it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace pinmask::cli {

// "--iters" for "iterations", ...; nullopt for a field no flag sets.
std::optional<std::string> flag_spelling(std::string_view field);

// `message` as the command line says it: every field reference spelled as its flag.
std::string spell_flags(std::string_view message);

// The table itself, (field, flag) sorted by field: for the test that checks it.
std::span<const std::pair<std::string_view, std::string_view>> flag_rows();

}  // namespace pinmask::cli
