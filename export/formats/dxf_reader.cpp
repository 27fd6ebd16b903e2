#include "export/formats/dxf_reader.hpp"

#include <charconv>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/decimal.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/xor_area.hpp"

namespace pinmask {
namespace {

constexpr int kCountDigits = 9;  // coordinates parsed as counts of 1e-9 drawing units
constexpr std::int64_t kCountsPerUnit = 1'000'000'000;
// A coordinate may be off the whole nanometre by this much (an inch written with 9 decimals is
// within 0.0127 nm of its nanometre); more is off the 1 nm database grid and refused.
constexpr double kOffGridToleranceNm = 0.02;

// The drawing unit: nanometres per unit and where it came from.
struct DrawingUnit {
    std::int64_t nm = 0;  // 0: not stated (micrometres are assumed at the first coordinate)
    std::string source;
};

struct Pair {
    int code = 0;
    std::string_view value;
    std::size_t line = 0;  // 1-based line of the group code
};

InvalidInput bad(std::size_t line, const std::string& rule) {
    return InvalidInput("dxf: line " + std::to_string(line) + ": " + rule);
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

class PairReader {
  public:
    explicit PairReader(std::string_view t) : t_(t) {}

    bool at_end() const { return pos_ >= t_.size(); }

    Pair next() {
        Pair p;
        p.line = line_ + 1;
        const std::string_view code = trim(read_line());
        const auto [ptr, ec] = std::from_chars(code.data(), code.data() + code.size(), p.code);
        if (ec != std::errc() || ptr != code.data() + code.size() || code.empty())
            throw bad(p.line,
                      "group code '" + std::string(code.substr(0, 20)) + "' is not an integer");
        if (at_end()) throw bad(p.line, "group code without a value: truncated");
        p.value = trim(read_line());
        return p;
    }

    // Puts the pair back so the next next() returns it again.
    void unread(const Pair& p) { saved_ = p; }
    Pair take() {
        if (saved_) {
            Pair p = *saved_;
            saved_.reset();
            return p;
        }
        if (at_end()) throw bad(line_ + 1, "file ends without EOF: truncated");
        return next();
    }

  private:
    std::string_view read_line() {
        const std::size_t nl = t_.find('\n', pos_);
        const std::size_t end = nl == std::string_view::npos ? t_.size() : nl;
        const std::string_view l = t_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++line_;
        return l;
    }

    std::string_view t_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
    std::optional<Pair> saved_;
};

// $INSUNITS codes with an exact nanometre size; the others (feet, miles, light years, ...,
// and unknown codes) are refused rather than guessed.
std::int64_t insunits_nm(int code) {
    switch (code) {
        case 1:
            return 25'400'000;  // inches
        case 4:
            return 1'000'000;  // millimetres
        case 5:
            return 10'000'000;  // centimetres
        case 6:
            return 1'000'000'000;  // metres
        case 9:
            return 25'400;  // mils
        case 12:
            return 1;  // nanometres
        case 13:
            return 1000;  // micrometres
        case 14:
            return 100'000'000;  // decimetres
        default:
            return 0;
    }
}

std::int64_t coordinate(const Pair& p, DrawingUnit& u) {
    std::int64_t count = 0;
    try {
        count = parse_scaled(p.value, kCountDigits, "dxf coordinate");
    } catch (const InvalidInput& e) {
        throw bad(p.line, e.what());
    }
    if (u.nm == 0) u = {1000, "assumed micrometres: the file states no unit"};
    const WideInt num = WideInt(count) * u.nm;
    WideInt q = num / kCountsPerUnit, r = num % kCountsPerUnit;
    if (r < 0) r += kCountsPerUnit, q -= 1;
    if (2 * r >= kCountsPerUnit) r -= kCountsPerUnit, q += 1;
    if (double(r < 0 ? -r : r) > kOffGridToleranceNm * double(kCountsPerUnit))
        throw bad(p.line, "coordinate '" + std::string(p.value.substr(0, 30)) +
                              "' is not on the 1 nm grid (" + u.source + ")");
    if (q > kMaxCoordNm || q < -kMaxCoordNm)
        throw bad(p.line,
                  "coordinate '" + std::string(p.value.substr(0, 30)) + "' is beyond 2^30 nm");
    return std::int64_t(q);
}

void set_unit(DrawingUnit& u, std::int64_t nm, const std::string& source, std::size_t line) {
    if (u.nm != 0 && u.nm != nm) throw bad(line, source + " contradicts " + u.source);
    if (u.nm == 0) u = {nm, source};
}

int integer(const Pair& p) {
    int v = 0;
    const auto [ptr, ec] = std::from_chars(p.value.data(), p.value.data() + p.value.size(), v);
    if (ec != std::errc() || ptr != p.value.data() + p.value.size())
        throw bad(p.line, "value '" + std::string(p.value.substr(0, 20)) + "' is not an integer");
    return v;
}

void check_bulge(const Pair& p) {
    for (char c : p.value)
        if (c >= '1' && c <= '9') throw bad(p.line, "arc segments (bulge) are not supported");
}

void finish(Ring ring, bool closed, std::size_t line, std::vector<Ring>& out) {
    if (ring.size() >= 2 && ring.front() == ring.back()) {
        ring.pop_back();
        closed = true;
    }
    if (!closed) throw bad(line, "polyline is not closed");
    if (ring.size() < 3) throw bad(line, "polyline has fewer than 3 vertices");
    out.push_back(std::move(ring));
}

// True when a group value is the number 0 ("0", "0.0", "-0.000", " 0"); false for anything else,
// malformed values included (the caller refuses those as not zero).
bool is_zero(std::string_view v) {
    const std::string t(v);
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    return end != t.c_str() && x == 0.0;
}

// Layers of the LAYER table a viewer does not draw: off (a negative colour, group 62) or frozen
// (flag 1 of group 70).
using HiddenLayers = std::map<std::string, std::string, std::less<>>;  // name -> "off" | "frozen"

// An entity group a viewer draws differently from the outline pinmask reads is refused by name:
// the entity on a hidden layer, invisible (60 = 1), with a colour < 0 (off), with a width
// (40, 41, 43: a wide polyline covers more than its outline) or a lineweight (370), or with an
// extrusion direction other than +z (210, 220, 230: the entity is mirrored or tilted into the
// plane).
void check_entity_group(const Pair& p, const HiddenLayers& hidden, std::string_view entity) {
    const std::string e(entity);
    switch (p.code) {
        case 8:
            if (auto it = hidden.find(p.value); it != hidden.end())
                throw bad(p.line, e + " on layer '" + std::string(p.value.substr(0, 30)) +
                                      "', which is " + it->second + ": a viewer does not draw it");
            break;
        case 60:
            if (p.value != "0") throw bad(p.line, e + " is invisible (group 60)");
            break;
        case 62:
            if (p.value.starts_with('-'))
                throw bad(p.line, e + " with a negative colour is off: a viewer does not draw it");
            break;
        case 40:
        case 41:
        case 43:
            if (!is_zero(p.value))
                throw bad(p.line, e + " width " + std::string(p.value.substr(0, 20)) + " (group " +
                                      std::to_string(p.code) +
                                      ") is not supported: a wide polyline covers more than its "
                                      "outline");
            break;
        case 370:  // lineweight in 1/100 mm; < 0 is by layer, by block or the default
            if (!p.value.starts_with('-') && !is_zero(p.value))
                throw bad(p.line, e + " lineweight " + std::string(p.value.substr(0, 20)) +
                                      " (group 370) is not supported: a viewer or plotter draws "
                                      "the outline that wide");
            break;
        case 210:
        case 220:
            if (!is_zero(p.value))
                throw bad(p.line, e + " with a tilted extrusion direction is not supported");
            break;
        case 230:
            if (p.value.starts_with('-'))
                throw bad(p.line, e + " with a negative extrusion direction (mirrored) is not "
                                      "supported");
            break;
        default:
            break;
    }
}

// An entity's layer (group 8), which identifies the film: one, and not empty (a second one or
// an empty name leaves the layer to the reading tool). `layer` is empty until it is given.
void take_layer(const Pair& p, std::string& layer) {
    if (!layer.empty()) throw bad(p.line, "entity with a second layer (group 8)");
    if (p.value.find_first_not_of(" \t") == std::string_view::npos)
        throw bad(p.line, "entity with an empty layer name (group 8)");
    layer = std::string(p.value);
}

// A LAYER table entry: its name and whether a viewer draws it.
void read_layer(PairReader& rd, HiddenLayers& hidden) {
    std::string name;
    bool off = false, frozen = false;
    Pair p;
    while ((p = rd.take()).code != 0) {
        if (p.code == 2) name = std::string(p.value);
        if (p.code == 62) off = p.value.starts_with('-');
        if (p.code == 70) frozen = integer(p) & 1;
    }
    rd.unread(p);
    if (frozen)
        hidden[name] = "frozen";
    else if (off)
        hidden[name] = "off";
}

// A POLYLINE entity: its own groups, then VERTEX entities, then SEQEND.
void read_polyline(PairReader& rd, std::size_t line, DrawingUnit& u, const HiddenLayers& hidden,
                   std::vector<Ring>& out, std::string& layer) {
    bool closed = false;
    Pair p;
    while ((p = rd.take()).code != 0) {
        check_entity_group(p, hidden, "POLYLINE");
        if (p.code == 8) take_layer(p, layer);
        if (p.code == 70) {
            const int flags = integer(p);
            if (flags & ~(1 | 128)) throw bad(p.line, "only plain 2D polylines are supported");
            closed = flags & 1;
        }
    }
    Ring ring;
    while (p.value == "VERTEX") {
        PointNm v;
        bool has_x = false, has_y = false;
        while ((p = rd.take()).code != 0) {
            check_entity_group(p, hidden, "VERTEX");
            if (p.code == 10) v.x = coordinate(p, u), has_x = true;
            if (p.code == 20) v.y = coordinate(p, u), has_y = true;
            if (p.code == 42) check_bulge(p);
        }
        if (!has_x || !has_y) throw bad(line, "VERTEX without 10/20 coordinates");
        ring.push_back(v);
    }
    if (p.value != "SEQEND") throw bad(p.line, "POLYLINE not ended by SEQEND");
    while ((p = rd.take()).code != 0) {
    }
    rd.unread(p);
    finish(std::move(ring), closed, line, out);
}

void read_lwpolyline(PairReader& rd, std::size_t line, DrawingUnit& u, const HiddenLayers& hidden,
                     std::vector<Ring>& out, std::string& layer) {
    bool closed = false;
    Ring ring;
    Pair p;
    while ((p = rd.take()).code != 0) {
        check_entity_group(p, hidden, "LWPOLYLINE");
        if (p.code == 8) take_layer(p, layer);
        if (p.code == 70) closed = integer(p) & 1;
        if (p.code == 10) ring.push_back({coordinate(p, u), 0});
        if (p.code == 20) {
            if (ring.empty()) throw bad(p.line, "20 before 10");
            ring.back().y = coordinate(p, u);
        }
        if (p.code == 42) check_bulge(p);
    }
    rd.unread(p);
    finish(std::move(ring), closed, line, out);
}

// A CIRCLE entity: centre 10/20, radius 40 (a true circle, FileGeometry circles).
void read_circle(PairReader& rd, std::size_t line, DrawingUnit& u, const HiddenLayers& hidden,
                 std::vector<CircleNm>& out, std::string& layer) {
    CircleNm c;
    bool has_x = false, has_y = false, has_r = false;
    Pair p;
    while ((p = rd.take()).code != 0) {
        if (p.code != 40) check_entity_group(p, hidden, "CIRCLE");  // 40: a circle's radius
        if (p.code == 8) take_layer(p, layer);
        if (p.code == 10) c.centre.x = coordinate(p, u), has_x = true;
        if (p.code == 20) c.centre.y = coordinate(p, u), has_y = true;
        if (p.code == 40) c.diameter_nm = 2 * coordinate(p, u), has_r = true;
    }
    rd.unread(p);
    if (!has_x || !has_y || !has_r) throw bad(line, "CIRCLE without 10/20/40 groups");
    if (c.diameter_nm <= 0) throw bad(line, "CIRCLE radius must be > 0");
    out.push_back(c);
}

}  // namespace

FileGeometry read_dxf(std::string_view text) {
    FileGeometry g;
    PairReader rd(text);
    std::string section;
    DrawingUnit unit;
    HiddenLayers hidden;
    std::set<std::string, std::less<>> layers_seen;  // g.layers
    TimeLimitPoll poll_time("reading the DXF file");
    for (;;) {
        poll_time();
        const Pair p = rd.take();
        if (p.code == 999) {
            for (const auto& [k, v] : parse_info(p.value)) g.info[k] = v;
            if (auto it = g.info.find("units"); it != g.info.end() && unit.nm == 0) {
                const std::string& name = it->second;
                const std::int64_t nm = name == "um"   ? 1000
                                        : name == "mm" ? 1'000'000
                                        : name == "in" ? 25'400'000
                                                       : 0;
                if (nm == 0) throw bad(p.line, "pinmask comment names unknown units=" + name);
                set_unit(unit, nm, "the pinmask comment's units=" + name, p.line);
            }
            continue;
        }
        if (p.code == 9 && section == "HEADER" && p.value == "$INSUNITS") {
            const Pair v = rd.take();
            if (v.code != 70) throw bad(v.line, "$INSUNITS without a 70 group");
            const int code = integer(v);
            const std::int64_t nm = insunits_nm(code);
            if (code != 0 && nm <= 0)
                throw bad(v.line, "$INSUNITS " + std::to_string(code) +
                                      " is not supported (pinmask reads 0 unitless, 1 in, 4 mm, "
                                      "5 cm, 6 m, 9 mil, 12 nm, 13 um, 14 dm)");
            // 0 (unitless) states nothing; a pinmask comment or micrometres decide.
            if (code != 0) {
                // The writer's own comment precedes the header; a later $INSUNITS wins only if
                // both agree, else the file contradicts itself.
                if (unit.nm != 0 && unit.nm != nm)
                    throw bad(v.line,
                              "$INSUNITS " + std::to_string(code) + " contradicts " + unit.source);
                unit = {nm, "$INSUNITS " + std::to_string(code)};
                g.info["insunits"] = std::to_string(code);
            }
            continue;
        }
        if (p.code != 0) {
            if (section.empty()) throw bad(p.line, "group outside a section");
            continue;
        }
        if (p.value == "EOF") break;
        if (p.value == "SECTION") {
            const Pair name = rd.take();
            if (name.code != 2) throw bad(name.line, "SECTION without a name");
            section = std::string(name.value);
            continue;
        }
        if (p.value == "ENDSEC") {
            section.clear();
            continue;
        }
        if (section == "TABLES" && p.value == "LAYER") {
            read_layer(rd, hidden);
            continue;
        }
        if (section != "ENTITIES") continue;
        std::string layer;  // set by group 8
        if (p.value == "POLYLINE")
            read_polyline(rd, p.line, unit, hidden, g.rings, layer);
        else if (p.value == "CIRCLE")
            read_circle(rd, p.line, unit, hidden, g.circles, layer);
        else if (p.value == "LWPOLYLINE")
            read_lwpolyline(rd, p.line, unit, hidden, g.rings, layer);
        else
            throw bad(p.line, "unsupported entity " + std::string(p.value.substr(0, 20)) +
                                  " (pinmask reads closed POLYLINE, LWPOLYLINE and CIRCLE only)");
        if (layer.empty()) layer = "0";  // an entity without group 8 is on layer 0
        if (layers_seen.insert(layer).second) g.layers.push_back(layer);
    }
    if (unit.nm != 0) g.info["unit_nm"] = std::to_string(unit.nm);
    // The file states no unit: the coordinates were read as micrometres (pinmask's historical
    // DXF unit); the faces say so.
    if (unit.source.starts_with("assumed")) g.info["unit_assumed"] = "um";
    return g;
}

}  // namespace pinmask
