// Paths and values as text. pinmask records the paths and values it was given in its JSON files
// (configs, sidecars, summaries), and JSON holds UTF-8 text only: a file name with invalid UTF-8
// (a Latin-1 name, raw bytes) failed with exit 1 after all the work, when the JSON was written.
// The faces refuse such text up front instead (cli/main.cpp every argument, io/capture_list the
// names in a --batch folder or list).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pinmask {

// The byte offset of the first byte that does not begin or continue a valid UTF-8 sequence
// (overlong forms, surrogates and code points beyond U+10FFFF included), or npos when `text` is
// valid UTF-8.
std::size_t invalid_utf8_at(std::string_view text);

// `text` for a message: valid UTF-8 as it is, every other byte as \xHH.
std::string printable_text(std::string_view text);

}  // namespace pinmask
