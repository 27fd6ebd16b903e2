// Field references in messages. A library names the setting at fault by its own field name in
// backquotes ("`iterations` = 0: must be >= 1"), never by a command-line flag or a Python
// keyword. Each face rewrites the references into its own spelling through one table
// (cli/options/flag_names for the command line, python/keyword_names for Python), so the
// libraries stay free of either face's words and both faces say the same thing.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace pinmask {

// "`name`": the reference to the field `name` inside a message.
std::string field_ref(std::string_view name);

// True when `text` can be a field name: letters, digits, '_' and '.', starting with a letter.
bool is_field_name(std::string_view text);

// A face's spelling of one field, or nullopt when the face has no spelling for it.
using FieldSpelling = std::optional<std::string> (*)(std::string_view field);

// `message` with every "`name`" reference replaced by spell(name), or by the bare name when the
// face has no spelling for it (a JSON key, say). Backquotes around anything that is not a field
// name are left alone.
std::string spell_fields(std::string_view message, FieldSpelling spell);

}  // namespace pinmask
