#include "io/json_strict.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/files/input_file.hpp"

namespace pinmask::io::json_strict {

void fail(const std::string& key_path, const std::string& rule) {
    throw InvalidInput((key_path.empty() ? std::string("(root)") : key_path) + ": " + rule);
}

OrderedJson finite_or_null(double v) {
    if (!std::isfinite(v)) return nullptr;
    return v;
}

namespace {

// "1 MiB", "1 GiB", "3 KiB" or "100 bytes": a byte limit as messages state it.
std::string byte_limit_text(std::uintmax_t bytes) {
    constexpr std::uintmax_t kKiB = 1024, kMiB = kKiB * 1024, kGiB = kMiB * 1024;
    if (bytes > 0 && bytes % kGiB == 0) return std::to_string(bytes / kGiB) + " GiB";
    if (bytes > 0 && bytes % kMiB == 0) return std::to_string(bytes / kMiB) + " MiB";
    if (bytes > 0 && bytes % kKiB == 0) return std::to_string(bytes / kKiB) + " KiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_bounded_file(const std::filesystem::path& path, const std::string& where,
                              std::uintmax_t max_bytes, const std::string& kind) {
    if (const auto problem = input_file_problem(path))
        throw InvalidInput(where + ": cannot read: " + *problem);
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw InvalidInput(where + ": cannot read: " + ec.message());
    if (size > max_bytes)
        throw InvalidInput(where + ": " + std::to_string(size) + " bytes is not " + kind +
                           " (at most " + byte_limit_text(max_bytes) + ")");
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    if (!in) throw InvalidInput(where + ": cannot read");
    return ss.str();
}

std::string join_path(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
}

std::string indexed(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

ObjectReader::ObjectReader(const Json& j, std::string path,
                           std::initializer_list<const char*> known)
    : j_(j), path_(std::move(path)), known_(known.begin(), known.end()) {
    if (!j_.is_object()) fail(path_, std::string("must be an object, got ") + j_.type_name());
}

void ObjectReader::reject_unknown() const {
    for (const auto& item : j_.items()) {
        if (std::find(known_.begin(), known_.end(), item.key()) == known_.end()) {
            std::string list;
            for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
            fail(join_path(path_, item.key()), "unknown key (known here: " + list + ")");
        }
    }
}

const Json& ObjectReader::required(const std::string& key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) fail(join_path(path_, key), "missing required key");
    return *it;
}

const Json* ObjectReader::optional(const std::string& key) const {
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
}

bool small_int(const Json& j, int& out) {
    if (j.is_number_unsigned()) {
        const auto u = j.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(INT_MAX)) return false;
        out = static_cast<int>(u);
        return true;
    }
    if (j.is_number_integer()) {
        const auto i = j.get<std::int64_t>();
        if (i < INT_MIN || i > INT_MAX) return false;
        out = static_cast<int>(i);
        return true;
    }
    return false;
}

int read_int(const Json& j, const std::string& path) {
    if (!j.is_number_integer()) {
        fail(path, std::string("must be an integer, got ") + j.type_name() + " " + j.dump());
    }
    int v = 0;
    if (!small_int(j, v)) fail(path, j.dump() + " is out of range");
    return v;
}

double read_number(const Json& j, const std::string& path) {
    if (!j.is_number()) fail(path, std::string("must be a number, got ") + j.type_name());
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "must be a finite number (got " + j.dump() + ")");
    return v;
}

double read_length_or_inf(const Json& j, const std::string& path) {
    if (j.is_string()) {
        if (j.get<std::string>() == "inf") return INFINITY;
        fail(path, "must be a number or the string \"inf\", got " + j.dump());
    }
    return read_number(j, path);
}

std::string read_string(const Json& j, const std::string& path) {
    if (!j.is_string()) fail(path, std::string("must be a string, got ") + j.type_name());
    std::string s = j.get<std::string>();
    // No name, path or word of pinmask's files holds one, and a path would be opened up to it.
    if (const auto at = s.find('\0'); at != std::string::npos)
        fail(path, "holds a NUL character (\\u0000) after \"" + s.substr(0, at) +
                       "\": no name or path can");
    return s;
}

bool read_bool(const Json& j, const std::string& path) {
    if (!j.is_boolean()) fail(path, std::string("must be true or false, got ") + j.type_name());
    return j.get<bool>();
}

std::pair<int, int> read_int_pair(const Json& j, const std::string& path, const char* what) {
    if (!j.is_array() || j.size() != 2) {
        fail(path, std::string("must be a two-element array ") + what + ", got " + j.dump());
    }
    return {read_int(j[0], indexed(path, 0)), read_int(j[1], indexed(path, 1))};
}

// pinmask's formats nest at most 4 levels. Each open level keeps its key path (O(depth) bytes),
// so unbounded nesting costs O(depth^2): 50k '[' took 4.5 GB and 40 s. Deeper input is refused.
constexpr std::size_t kMaxNestingDepth = 64;

Json parse_strict(const std::string& text, const std::string& streamed_path,
                  const std::function<void(const Json&, std::size_t)>& on_element) {
    struct Frame {
        bool object = false;
        bool streamed = false;  // an element of the streamed array: path built only when needed
        std::string path;
        std::set<std::string> keys;
        std::string last_key;
        std::size_t count = 0;  // arrays: elements so far; streamed elements: their index
    };
    const bool streaming = !streamed_path.empty() && on_element;
    std::vector<Frame> stack;
    const auto path_of = [&](Frame& f) -> const std::string& {
        if (f.streamed && f.path.empty()) f.path = indexed(streamed_path, f.count);
        return f.path;
    };
    // A value is complete: true keeps it in the tree.
    const auto finished = [&](const Json& value) {
        if (stack.empty() || stack.back().object) return true;
        Frame& parent = stack.back();
        const std::size_t index = parent.count++;
        if (!streaming || parent.path != streamed_path) return true;
        on_element(value, index);
        return false;
    };
    auto cb = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
            case Json::parse_event_t::object_start:
            case Json::parse_event_t::array_start: {
                if (stack.size() >= kMaxNestingDepth) {
                    fail(stack.empty() ? "(root)" : path_of(stack.back()),
                         "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels");
                }
                Frame f;
                f.object = event == Json::parse_event_t::object_start;
                if (!stack.empty()) {
                    Frame& parent = stack.back();
                    if (parent.object) {
                        f.path = join_path(path_of(parent), parent.last_key);
                    } else if (streaming && parent.path == streamed_path) {
                        f.streamed = true;
                        f.count = parent.count;
                    } else {
                        f.path = indexed(path_of(parent), parent.count);
                    }
                }
                stack.push_back(std::move(f));
                return true;
            }
            case Json::parse_event_t::object_end:
            case Json::parse_event_t::array_end:
                if (!stack.empty()) stack.pop_back();
                return finished(parsed);
            case Json::parse_event_t::key: {
                const std::string key = parsed.get<std::string>();
                Frame& f = stack.back();
                if (!f.keys.insert(key).second) {
                    fail(join_path(path_of(f), key),
                         "duplicate key (each key may appear once per object)");
                }
                f.last_key = key;
                return true;
            }
            case Json::parse_event_t::value:
                return finished(parsed);
        }
        return true;
    };
    return Json::parse(text, cb);
}

namespace {

bool is_scalar(const OrderedJson& j) { return !j.is_array() && !j.is_object(); }

void pretty_into(const OrderedJson& j, const std::string& path, int indent,
                 const std::string& raw_path, const RawWriter& raw, std::string& out) {
    if (raw && !raw_path.empty() && path == raw_path) {
        raw(out, indent);
        return;
    }
    const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
    const std::string close_pad(static_cast<std::size_t>(indent), ' ');
    if (j.is_object()) {
        if (j.empty()) {
            out += "{}";
            return;
        }
        out += "{\n";
        bool first = true;
        for (const auto& item : j.items()) {
            if (!first) out += ",\n";
            first = false;
            out += pad + OrderedJson(item.key()).dump() + ": ";
            pretty_into(item.value(), join_path(path, item.key()), indent + 2, raw_path, raw, out);
        }
        out += "\n" + close_pad + "}";
    } else if (j.is_array()) {
        if (std::all_of(j.begin(), j.end(), is_scalar)) {
            out += "[";
            for (std::size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
            out += "]";
            return;
        }
        out += "[\n";
        for (std::size_t i = 0; i < j.size(); ++i) {
            if (i) out += ",\n";
            out += pad;
            pretty_into(j[i], indexed(path, i), indent + 2, raw_path, raw, out);
        }
        out += "\n" + close_pad + "]";
    } else {
        out += j.dump();
    }
}

}  // namespace

std::string pretty(const OrderedJson& j, const std::string& raw_path, const RawWriter& raw) {
    std::string out;
    pretty_into(j, "", 0, raw_path, raw, out);
    return out;
}

std::string json_error_words(const nlohmann::json::exception& e) {
    std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0) {
        const std::size_t end = what.find("] ");
        if (end != std::string::npos) what.erase(0, end + 2);
    }
    return what;
}

}  // namespace pinmask::io::json_strict
