// A face's spelling table (cli/options/flag_names, python/keyword_names): rows of (field name as
// the libraries write it, the face's spelling), sorted by field so that a field is found by
// binary search.
#pragma once

#include <algorithm>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

namespace pinmask {

using SpellingRow = std::pair<std::string_view, std::string_view>;

// The spelling of `field` in `rows` (sorted by field), or nullopt when no row has it.
inline std::optional<std::string_view> find_spelling(std::span<const SpellingRow> rows,
                                                     std::string_view field) {
    const auto it =
        std::lower_bound(rows.begin(), rows.end(), field,
                         [](const SpellingRow& row, std::string_view f) { return row.first < f; });
    if (it == rows.end() || it->first != field) return std::nullopt;
    return it->second;
}

}  // namespace pinmask
