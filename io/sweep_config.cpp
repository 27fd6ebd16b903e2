#include "io/sweep_config.hpp"

#include <algorithm>

#include "core/errors/error.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {
namespace {

using namespace json_strict;

// A sweep file is a few kilobytes; anything this large is not one.
constexpr std::uintmax_t kMaxSweepBytes = 1 << 20;

std::vector<std::string> split_dots(const std::string& key, const std::string& where) {
    std::vector<std::string> parts;
    std::string part;
    for (char ch : key + ".") {
        if (ch != '.') {
            part += ch;
            continue;
        }
        if (part.empty()) fail(where, "'" + key + "' is not a key path (empty part)");
        parts.push_back(part);
        part.clear();
    }
    return parts;
}

// Checks a varied key against the sweep rules that the search codec alone cannot see.
void check_key(const std::string& key, const Json& base, const std::string& where) {
    const std::vector<std::string> parts = split_dots(key, where);
    for (const char* fixed : {"format", "version", "generator", "kernel_resolved"})
        if (parts.front() == fixed) fail(where, "'" + key + "' cannot vary in a sweep");
    if (parts.front() == "time")
        fail(where,
             "a sweep runs every point on an evaluation budget (evaluations_per_chain), not a "
             "time budget: results must not depend on the machine or the rank count");
    if (parts.front() == "optics" && parts.size() > 1 && !base.contains("optics"))
        fail(where,
             "varies a camera field, but base has no \"optics\" object to vary (give it "
             "with all its keys, as in a search.config.json)");
}

// Sets the value at a dotted key path, creating objects on the way.
void set_path(Json& doc, const std::string& key, const Json& value, const std::string& where) {
    Json* node = &doc;
    const std::vector<std::string> parts = split_dots(key, where);
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
        Json& next = (*node)[parts[i]];
        if (next.is_null()) next = Json::object();
        if (!next.is_object()) fail(where, "'" + key + "': base." + parts[i] + " is not an object");
        node = &next;
    }
    (*node)[parts.back()] = value;
}

SweepValue sweep_value(const std::string& key, const Json& v) {
    SweepValue out{key, v.is_string() ? v.get<std::string>() : v.dump(), std::nullopt};
    if (v.is_number()) out.number = v.get<double>();
    return out;
}

// The rules tying a point's keys together (the search codec accepts each key alone).
void check_point(const Json& doc) {
    if (const auto noise = doc.find("noise"); noise != doc.end() && noise->is_object()) {
        const auto model = noise->find("model");
        const bool photon = model != noise->end() && *model == "photon";
        if (photon && noise->contains("snr_db"))
            fail("noise.snr_db", "belongs to the gaussian model, but noise.model is \"photon\"");
        if (!photon) {
            for (const char* k : {"read_noise_e", "dark_current_e", "full_well_e", "adc_bits",
                                  "film_optical_density"}) {
                if (noise->contains(k))
                    fail(std::string("noise.") + k,
                         "belongs to the photon model, but noise.model is not \"photon\"");
            }
        }
    }
    if (const auto t = doc.find("threads"); t != doc.end() && *t == 0)
        fail("threads",
             "must be >= 1 in a sweep (0, all cores, would make a point's chains and "
             "so its result depend on the machine)");
    const auto evals = doc.find("evaluations_per_chain");
    if (evals == doc.end() || !evals->is_number_integer() || evals->get<std::int64_t>() < 1)
        fail("evaluations_per_chain",
             "a sweep needs an evaluation budget >= 1 at every point (points are reproducible, "
             "whatever the machine or rank count); got " +
                 (evals == doc.end() ? std::string("none") : evals->dump()));
}

SweepPoint make_point(const Json& base, const std::vector<std::pair<std::string, Json>>& values,
                      const std::string& label) {
    Json doc = base;
    SweepPoint p;
    try {
        for (const auto& kv : values) {
            set_path(doc, kv.first, kv.second, kv.first);
            p.values.push_back(sweep_value(kv.first, kv.second));
        }
        if (!doc.contains("format")) doc["format"] = kSearchConfigFormat;
        if (!doc.contains("version")) doc["version"] = kSearchConfigVersion;
        if (!doc.contains("threads")) doc["threads"] = 1;
        check_point(doc);
        p.config_text = doc.dump(2);
        p.config = parse_search_config(p.config_text);
    } catch (const InvalidInput& e) {
        throw InvalidInput(label + ": " + e.what());
    }
    return p;
}

std::string point_label(const std::string& where,
                        const std::vector<std::pair<std::string, Json>>& values) {
    std::string s = where + " (";
    for (std::size_t i = 0; i < values.size(); ++i)
        s += (i ? ", " : "") + values[i].first + " = " + values[i].second.dump();
    return s + ")";
}

}  // namespace

SweepConfig parse_sweep_config(const std::string& text) {
    Json j;
    try {
        j = parse_strict(text);
    } catch (const nlohmann::json::exception& e) {
        throw InvalidInput(std::string("invalid JSON: ") + json_error_words(e));
    }
    ObjectReader r(j, "", {"format", "version", "base", "grid", "points"});
    if (read_string(r.required("format"), "format") != kSweepFormat)
        fail("format", "must be \"" + std::string(kSweepFormat) + "\" (not a sweep file)");
    if (const int v = read_int(r.required("version"), "version"); v != kSweepVersion)
        fail("version", std::to_string(v) + " is not supported (this pinmask reads version " +
                            std::to_string(kSweepVersion) + ")");
    r.reject_unknown();
    Json base = Json::object();
    if (const Json* b = r.optional("base")) {
        if (!b->is_object()) fail("base", std::string("must be an object, got ") + b->type_name());
        base = *b;
    }
    const Json* grid = r.optional("grid");
    const Json* points = r.optional("points");
    if (grid && points) fail("points", "give either \"grid\" or \"points\", not both");
    if (!grid && !points) fail("grid", "missing: give a \"grid\" (or a \"points\" list)");

    SweepConfig out;
    out.text = pretty(OrderedJson::parse(j.dump()));
    if (grid) {
        if (!grid->is_object() || grid->empty())
            fail("grid", "empty grid: give at least one key with a list of values");
        std::size_t count = 1;
        for (const auto& item : grid->items()) {
            const std::string where = "grid." + item.key();
            check_key(item.key(), base, where);
            if (!item.value().is_array() || item.value().empty())
                fail(where, "must be a non-empty list of values, got " + item.value().dump());
            if (item.value().size() > kMaxSweepPoints / count)
                fail(where, "the grid has more than " + std::to_string(kMaxSweepPoints) +
                                " points (each point is one whole search)");
            count *= item.value().size();
            out.keys.push_back(item.key());
        }
        for (std::size_t i = 0; i < count; ++i) {
            std::vector<std::pair<std::string, Json>> values(out.keys.size());
            std::size_t rest = i;
            for (std::size_t k = out.keys.size(); k-- > 0;) {
                const Json& list = (*grid)[out.keys[k]];
                values[k] = {out.keys[k], list[rest % list.size()]};
                rest /= list.size();
            }
            out.points.push_back(
                make_point(base, values, point_label("grid point " + std::to_string(i), values)));
        }
        return out;
    }
    if (!points->is_array() || points->empty())
        fail("points", "empty list: give at least one point (an object of key: value)");
    if (points->size() > kMaxSweepPoints)
        fail("points", std::to_string(points->size()) + " points exceed " +
                           std::to_string(kMaxSweepPoints) + " (each point is one whole search)");
    for (std::size_t i = 0; i < points->size(); ++i) {
        const Json& pt = (*points)[i];
        const std::string where = indexed("points", i);
        if (!pt.is_object()) fail(where, std::string("must be an object, got ") + pt.type_name());
        for (const auto& item : pt.items()) {
            check_key(item.key(), base, where + "." + item.key());
            if (std::find(out.keys.begin(), out.keys.end(), item.key()) == out.keys.end())
                out.keys.push_back(item.key());
        }
    }
    std::sort(out.keys.begin(), out.keys.end());
    for (std::size_t i = 0; i < points->size(); ++i) {
        const Json& pt = (*points)[i];
        std::vector<std::pair<std::string, Json>> values;
        for (const auto& item : pt.items()) values.emplace_back(item.key(), item.value());
        SweepPoint p = make_point(base, values, point_label(indexed("points", i), values));
        // Keys this point leaves at the base value: shown as "-" (base) in tables.
        std::vector<SweepValue> all;
        for (const std::string& key : out.keys) {
            const auto it = std::find_if(p.values.begin(), p.values.end(),
                                         [&](const SweepValue& v) { return v.key == key; });
            all.push_back(it != p.values.end() ? *it : SweepValue{key, "-", std::nullopt});
        }
        p.values = all;
        out.points.push_back(std::move(p));
    }
    return out;
}

SweepConfig read_sweep_config(const std::filesystem::path& path) {
    return parse_bounded_file(path, "SWEEP", kMaxSweepBytes, "a sweep file", parse_sweep_config);
}

}  // namespace pinmask::io
