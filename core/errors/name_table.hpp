// One name table per enum: a constexpr array of (value, name) pairs that is the only place an
// enum's spelling is written. name_of, parse_name and names_of read it, so the CLI, Python and
// JSON all spell a value the same way and an unknown name is an error naming the field, the
// value and the names accepted (never a fall-through to some default).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"

namespace pinmask {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<E, const char*>, N>;

// The names joined by `separator` in table order ("a | b | c").
template <class E, std::size_t N>
std::string names_of(const NameTable<E, N>& table, std::string_view separator = " | ") {
    std::string out;
    for (const auto& entry : table) {
        if (!out.empty()) out += separator;
        out += entry.second;
    }
    return out;
}

// The names in table order, as a list (CLI11's IsMember, Python checks).
template <class E, std::size_t N>
std::vector<std::string> name_list(const NameTable<E, N>& table) {
    std::vector<std::string> out;
    for (const auto& entry : table) out.emplace_back(entry.second);
    return out;
}

// The name of `value`; InvalidInput naming `what` for a value outside the table (an enum
// variable holding a number no enumerator has).
template <class E, std::size_t N>
const char* name_of(const NameTable<E, N>& table, E value, std::string_view what) {
    for (const auto& entry : table)
        if (entry.first == value) return entry.second;
    throw invalid_field(std::string(what), std::to_string(static_cast<long long>(value)),
                        "is not one of " + names_of(table));
}

// The name of `value`, or `fallback` for a value outside the table (where a name is only
// reported, never parsed back).
template <class E, std::size_t N>
const char* name_or(const NameTable<E, N>& table, E value, const char* fallback) {
    for (const auto& entry : table)
        if (entry.first == value) return entry.second;
    return fallback;
}

// The value named `name`; InvalidInput naming `field`, the value and the names otherwise.
template <class E, std::size_t N>
E parse_name(const NameTable<E, N>& table, std::string_view name, std::string_view field) {
    for (const auto& entry : table)
        if (name == entry.second) return entry.first;
    throw invalid_field(std::string(field), std::string(name), "must be one of " + names_of(table));
}

}  // namespace pinmask
