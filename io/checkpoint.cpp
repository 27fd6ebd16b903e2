#include "io/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/atomic_file.hpp"
#include "io/fnv1a.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {
namespace {

using namespace json_strict;

// A checkpoint holds a few KiB per chain (the generator state); 1 GiB is far past any real run.
constexpr std::uintmax_t kMaxCheckpointBytes = std::uintmax_t{1} << 30;
// A chain logs its best at 1, 2, .., 16 evaluations and then at ~19 % steps: 1e9 evaluations
// (the bound of every face) make about 130 entries. A longer log is no chain's: refused before
// it is read (a 300,000-entry log once took minutes to resume).
constexpr std::size_t kMaxLogEntries = 4096;

OrderedJson pattern_json(const Pattern& p) {
    OrderedJson holes = OrderedJson::array();
    for (const Cell& c : p.pinholes) holes.push_back({c.row, c.col});
    return {{"n", p.n},
            {"tiles_rows", p.tiles_rows},
            {"tiles_cols", p.tiles_cols},
            {"min_spacing_cells", p.min_spacing_cells},
            {"pinholes", holes}};
}

Pattern read_pattern(const Json& j, const std::string& path) {
    ObjectReader r(j, path, {"n", "tiles_rows", "tiles_cols", "min_spacing_cells", "pinholes"});
    r.reject_unknown();
    Pattern p;
    p.n = read_int(r.required("n"), r.path("n"));
    p.tiles_rows = read_int(r.required("tiles_rows"), r.path("tiles_rows"));
    p.tiles_cols = read_int(r.required("tiles_cols"), r.path("tiles_cols"));
    p.min_spacing_cells = read_number(r.required("min_spacing_cells"), r.path("min_spacing_cells"));
    const Json& holes = r.required("pinholes");
    if (!holes.is_array()) fail(r.path("pinholes"), "must be an array of [row, col]");
    for (std::size_t i = 0; i < holes.size(); ++i) {
        const auto [row, col] =
            read_int_pair(holes[i], indexed(r.path("pinholes"), i), "[row, col]");
        p.pinholes.push_back({row, col});
    }
    try {
        validate(p);
    } catch (const InvalidInput& e) {
        fail(path, e.what());
    }
    return p;
}

// null (no value yet) -> +inf; otherwise a finite number.
double read_objective(const Json& j, const std::string& path) {
    return j.is_null() ? INFINITY : read_number(j, path);
}

std::int64_t read_count(const Json& j, const std::string& path) {
    if (!j.is_number_integer() || j.get<std::int64_t>() < 0) fail(path, "must be an integer >= 0");
    return j.get<std::int64_t>();
}

OrderedJson chain_json(const ChainState& s) {
    std::ostringstream rng;
    rng << s.rng;
    OrderedJson log = OrderedJson::array();
    for (const auto& [e, best] : s.checkpoints) log.push_back({e, finite_or_null(best)});
    OrderedJson top = OrderedJson::array();
    for (const auto& item : s.top.items())
        top.push_back({{"objective", finite_or_null(item.objective)},
                       {"pattern", pattern_json(item.pattern)}});
    OrderedJson per_holes = OrderedJson::array();
    for (const auto& [k, best] : s.best_per_holes)
        for (const auto& item : best.items())
            per_holes.push_back({{"holes", k},
                                 {"objective", finite_or_null(item.objective)},
                                 {"pattern", pattern_json(item.pattern)}});
    return {{"rng", rng.str()},
            {"evaluations", s.evaluations},
            {"best_objective", finite_or_null(s.best_objective)},
            {"next_log_at", s.next_checkpoint},
            {"log", log},
            {"top_capacity", s.top.capacity()},
            {"top", top},
            {"start", s.start ? pattern_json(*s.start) : OrderedJson(nullptr)},
            {"best_per_holes", per_holes}};
}

// Why `text` is not the text form of a std::mt19937_64 state, or "": 312 words of 0..2^64-1
// and an index of 0..312, each in plain decimal digits. The stream reader alone would take
// "-5" as 2^64 - 5 and read a wrapped state.
std::string rng_state_problem(const std::string& text) {
    constexpr std::size_t kWords = std::mt19937_64::state_size;
    std::istringstream in(text);
    std::string token;
    std::size_t count = 0;
    while (in >> token) {
        ++count;
        if (count > kWords + 1) return "more than " + std::to_string(kWords + 1) + " numbers";
        std::uint64_t v = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
        if (token.empty() || token[0] == '-' || token[0] == '+' || ec != std::errc() ||
            end != token.data() + token.size())
            return "number " + std::to_string(count) + " ('" + token.substr(0, 24) +
                   "') is not an integer of 0..2^64-1";
        if (count == kWords + 1 && v > kWords)
            return "its index " + token + " is beyond " + std::to_string(kWords);
    }
    if (count != kWords + 1)
        return std::to_string(count) + " numbers, not " + std::to_string(kWords + 1);
    return "";
}

// The checksum covers the file's every byte: the text as written with the checksum's own value
// set to 16 zeros. Its value is the string after the last "checksum" key (any JSON spacing).
constexpr const char* kChecksumZero = "0000000000000000";

std::size_t checksum_value_at(const std::string& text) {
    std::size_t at = text.rfind("\"checksum\"");
    if (at == std::string::npos) return at;
    at += 10;
    const auto skip_space = [&] {
        while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    };
    skip_space();
    if (at >= text.size() || text[at] != ':') return std::string::npos;
    ++at;
    skip_space();
    if (at + 18 > text.size() || text[at] != '"' || text[at + 17] != '"') return std::string::npos;
    return at + 1;
}

ChainState read_chain(const Json& j, const std::string& path) {
    ObjectReader r(j, path,
                   {"rng", "evaluations", "best_objective", "next_log_at", "log", "top_capacity",
                    "top", "start", "best_per_holes"});
    r.reject_unknown();
    ChainState s;
    const std::string rng_text = read_string(r.required("rng"), r.path("rng"));
    if (const std::string why = rng_state_problem(rng_text); !why.empty())
        fail(r.path("rng"), "is not a std::mt19937_64 state (312 words and an index): " + why);
    std::istringstream rng(rng_text);
    rng >> s.rng;
    if (!rng) fail(r.path("rng"), "is not a std::mt19937_64 state (312 words and an index)");
    s.evaluations = read_count(r.required("evaluations"), r.path("evaluations"));
    s.best_objective = read_objective(r.required("best_objective"), r.path("best_objective"));
    s.next_checkpoint = read_count(r.required("next_log_at"), r.path("next_log_at"));
    const Json& log = r.required("log");
    if (!log.is_array()) fail(r.path("log"), "must be an array of [evaluations, best]");
    if (log.size() > kMaxLogEntries) {
        fail(r.path("log"),
             "has " + std::to_string(log.size()) + " entries; a chain's log has at most " +
                 std::to_string(kMaxLogEntries) + " (about 130 for 1e9 evaluations)");
    }
    for (std::size_t i = 0; i < log.size(); ++i) {
        const std::string p = indexed(r.path("log"), i);
        if (!log[i].is_array() || log[i].size() != 2) fail(p, "must be [evaluations, best]");
        s.checkpoints.push_back(
            {read_count(log[i][0], p + "[0]"), read_objective(log[i][1], p + "[1]")});
        if (i > 0 && s.checkpoints[i].first <= s.checkpoints[i - 1].first)
            fail(p + "[0]", "must be above the previous entry's evaluations");
        if (s.checkpoints[i].first > s.evaluations)
            fail(p + "[0]", "must be at most the chain's evaluations");
    }
    const int capacity = read_int(r.required("top_capacity"), r.path("top_capacity"));
    if (capacity < 1 || capacity > 1000) fail(r.path("top_capacity"), "must be in 1..1000");
    s.top = TopCandidates(capacity);
    const Json& top = r.required("top");
    if (!top.is_array() || top.size() > static_cast<std::size_t>(capacity))
        fail(r.path("top"), "must be an array of at most top_capacity candidates");
    double previous = -INFINITY;
    for (std::size_t i = 0; i < top.size(); ++i) {
        const std::string p = indexed(r.path("top"), i);
        ObjectReader t(top[i], p, {"objective", "pattern"});
        t.reject_unknown();
        const double objective = read_number(t.required("objective"), t.path("objective"));
        if (objective < previous) fail(t.path("objective"), "candidates must be best first");
        previous = objective;
        const std::size_t before = s.top.items().size();
        s.top.offer(read_pattern(t.required("pattern"), t.path("pattern")), objective);
        if (s.top.items().size() != before + 1) fail(p, "repeats a pattern already listed");
    }
    const Json& start = r.required("start");
    if (!start.is_null()) s.start = read_pattern(start, r.path("start"));
    // With a pinhole-count range (search --holes A..B): the best pattern at every K seen.
    if (const Json* per_holes = r.optional("best_per_holes")) {
        if (!per_holes->is_array())
            fail(r.path("best_per_holes"), "must be an array of {holes, objective, pattern}");
        for (std::size_t i = 0; i < per_holes->size(); ++i) {
            const std::string p = indexed(r.path("best_per_holes"), i);
            ObjectReader b((*per_holes)[i], p, {"holes", "objective", "pattern"});
            b.reject_unknown();
            const int k = read_int(b.required("holes"), b.path("holes"));
            if (k < 1) fail(b.path("holes"), "must be >= 1");
            const auto [it, fresh] = s.best_per_holes.try_emplace(k, 1);
            if (!fresh) fail(b.path("holes"), "repeats a pinhole count already listed");
            it->second.offer(read_pattern(b.required("pattern"), b.path("pattern")),
                             read_objective(b.required("objective"), b.path("objective")));
        }
    }
    return s;
}

}  // namespace

std::string checkpoint_to_json(const SearchCheckpointFile& c) {
    OrderedJson chains = OrderedJson::array();
    for (const ChainState& s : c.chains) chains.push_back(chain_json(s));
    const OrderedJson j{{"format", kCheckpointFormat},
                        {"version", kCheckpointVersion},
                        {"config", c.config},
                        {"segment", c.segment},
                        {"evaluations_between_boundaries", c.every},
                        {"chains", chains},
                        {"checksum", kChecksumZero}};
    std::string text = pretty(j) + "\n";
    text.replace(checksum_value_at(text), 16, fnv1a64_hex(text));
    return text;
}

SearchCheckpointFile parse_checkpoint(const std::string& text) {
    Json j;
    try {
        j = parse_strict(text);
    } catch (const nlohmann::json::exception& e) {
        fail("(root)", std::string("not valid JSON: ") + json_error_words(e));
    }
    ObjectReader r(j, "",
                   {"format", "version", "config", "segment", "evaluations_between_boundaries",
                    "chains", "checksum"});
    r.reject_unknown();
    if (read_string(r.required("format"), "format") != kCheckpointFormat)
        fail("format", std::string("must be \"") + kCheckpointFormat + "\"");
    if (const int version = read_int(r.required("version"), "version");
        version != kCheckpointVersion) {
        fail("version",
             "must be " + std::to_string(kCheckpointVersion) +
                 (version == 1 ? " (version 1 checkpoints carry no checksum: resume with the "
                                 "pinmask that wrote it, or start the run again)"
                               : ""));
    }
    {  // the checksum first: an edited file is refused as such, whatever field was edited
        const std::string claimed = read_string(r.required("checksum"), "checksum");
        const std::size_t at = checksum_value_at(text);
        if (claimed.size() != 16 || at == std::string::npos || text.compare(at, 16, claimed) != 0)
            fail("checksum", "must be the 16 hex digits pinmask wrote");
        std::string zeroed = text;
        zeroed.replace(at, 16, kChecksumZero);
        if (fnv1a64_hex(zeroed) != claimed) {
            fail("checksum", claimed + " is not the file's (" + fnv1a64_hex(zeroed) +
                                 "): the checkpoint was changed after it was written");
        }
    }
    SearchCheckpointFile c;
    const Json& config = r.required("config");
    if (!config.is_object()) fail("config", "must be an object");
    c.config = OrderedJson::parse(config.dump());
    c.segment = read_count(r.required("segment"), "segment");
    c.every =
        read_count(r.required("evaluations_between_boundaries"), "evaluations_between_boundaries");
    if (c.segment < 1) fail("segment", "must be >= 1");
    if (c.every < 1) fail("evaluations_between_boundaries", "must be >= 1");
    const Json& chains = r.required("chains");
    if (!chains.is_array() || chains.empty()) fail("chains", "must be a non-empty array");
    for (std::size_t i = 0; i < chains.size(); ++i)
        c.chains.push_back(read_chain(chains[i], indexed("chains", i)));
    return c;
}

void write_checkpoint(const std::filesystem::path& path, const SearchCheckpointFile& c) {
    write_bytes_atomic(path, checkpoint_to_json(c));
}

SearchCheckpointFile read_checkpoint(const std::filesystem::path& path) {
    return parse_bounded_file(path, field_ref("resume"), kMaxCheckpointBytes, "a search checkpoint",
                              parse_checkpoint);
}

std::vector<std::string> differing_keys(const nlohmann::ordered_json& a,
                                        const nlohmann::ordered_json& b) {
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    std::vector<std::string> out;
    for (const std::string& k : keys) {
        // Compared as unordered JSON: a file's nested objects may list keys in another order.
        if (!a.contains(k) || !b.contains(k) ||
            Json::parse(a.at(k).dump()) != Json::parse(b.at(k).dump()))
            out.push_back(k);
    }
    return out;
}

}  // namespace pinmask::io
