// Strict JSON reading and deterministic JSON writing for pinmask's own file formats (the mask
// codec first). Reading: every error is InvalidInput "<key path>: <rule>", key paths written
// like "pattern.pinholes[3][0]" ("(root)" for the document); repeated keys are rejected instead
// of silently keeping the last; unknown keys are rejected by ObjectReader. Writing: 2-space
// indent, keys in the order of the ordered_json, arrays of scalars on one line, numbers in
// nlohmann's shortest round-trip form.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"

namespace pinmask::io::json_strict {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

// Throws InvalidInput("<key_path>: <rule>").
[[noreturn]] void fail(const std::string& key_path, const std::string& rule);

// "a" + "b" -> "a.b" ("" + "b" -> "b"); "a" + 3 -> "a[3]".
std::string join_path(const std::string& parent, const std::string& key);
std::string indexed(const std::string& path, std::size_t i);

// The keys of one JSON object (throws unless j is an object): required/optional lookup, and
// rejection of keys not in `known`, naming the key and listing the known ones.
class ObjectReader {
  public:
    ObjectReader(const Json& j, std::string path, std::initializer_list<const char*> known);
    void reject_unknown() const;
    const Json& required(const std::string& key) const;
    const Json* optional(const std::string& key) const;  // nullptr when absent
    std::string path(const std::string& key) const { return join_path(path_, key); }

  private:
    const Json& j_;
    std::string path_;
    std::vector<std::string> known_;
};

// Typed reads; each throws InvalidInput naming `path` and the rule it breaks.
int read_int(const Json& j, const std::string& path);               // an integer within int range
double read_number(const Json& j, const std::string& path);         // any finite number
double read_length_or_inf(const Json& j, const std::string& path);  // number or "inf" -> +inf
std::string read_string(const Json& j, const std::string& path);    // no NUL character inside
bool read_bool(const Json& j, const std::string& path);
// A two-element integer array; `what` names the elements in the message, e.g. "[row, col]".
std::pair<int, int> read_int_pair(const Json& j, const std::string& path, const char* what);
// j as an int when it is an integer within int range; false (no message) otherwise.
bool small_int(const Json& j, int& out);

// Parses text, rejecting repeated keys in an object. Each element of the array at key path
// `streamed_path` (if any) is passed to on_element(element, index) as soon as it is parsed and
// left out of the returned tree, so a long array costs what the caller keeps, not a JSON node
// per number. Throws InvalidInput for repeated keys (and whatever on_element throws), and
// nlohmann's parse_error / out_of_range for syntax errors and overflowing numbers.
Json parse_strict(const std::string& text, const std::string& streamed_path = "",
                  const std::function<void(const Json&, std::size_t)>& on_element = {});

// A JSON library error in the project's words: nlohmann's "[json.exception.parse_error.101]
// parse error at line 1, column 3: syntax error ..." without its bracketed id (which means
// nothing to a user), first letter as it was.
std::string json_error_words(const nlohmann::json::exception& e);

// Writes the value at key path `raw_path` in place of the tree's: called with the output and
// the indent (spaces) of the line where the value starts.
using RawWriter = std::function<void(std::string& out, int indent)>;

// v as a JSON number, or null when it is not finite (JSON has no inf or NaN).
OrderedJson finite_or_null(double v);

// Pretty-prints j (see the file comment); the value at raw_path, if any, comes from raw.
// No trailing newline.
std::string pretty(const OrderedJson& j, const std::string& raw_path = "",
                   const RawWriter& raw = {});

// The whole text of a file that must hold at most max_bytes (a configuration, a checkpoint),
// checked by size before it is read. `where` ("<setting> <path>") begins every message:
// "<where>: cannot read: <reason>", "<where>: cannot read", and for a larger file
// "<where>: N bytes is not <kind> (at most <max_bytes as MiB or GiB>)"; all InvalidInput.
std::string read_bounded_file(const std::filesystem::path& path, const std::string& where,
                              std::uintmax_t max_bytes, const std::string& kind);

// parse(read_bounded_file(path, where, ...)) with where = "<setting> <path>", where also
// prefixed to any InvalidInput that parse throws ("<setting> <path>: <key path>: <rule>").
template <class Parse>
auto parse_bounded_file(const std::filesystem::path& path, const std::string& setting,
                        std::uintmax_t max_bytes, const std::string& kind, Parse parse) {
    const std::string where = setting + " " + path.string();
    const std::string text = read_bounded_file(path, where, max_bytes, kind);
    try {
        return parse(text);
    } catch (const InvalidInput& e) {
        throw InvalidInput(where + ": " + e.what());
    }
}

}  // namespace pinmask::io::json_strict
