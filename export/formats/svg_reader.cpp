#include "export/formats/svg_reader.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>

#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/decimal.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask {
namespace {

constexpr int kMicrometreDigits = 3;

InvalidInput bad(std::size_t offset, const std::string& rule) {
    return InvalidInput("svg: at byte " + std::to_string(offset) + ": " + rule);
}

// The value of attribute `name` inside the tag text, or npos-marked empty view.
bool attribute(std::string_view tag, std::string_view name, std::string_view& value) {
    std::size_t pos = 0;
    while ((pos = tag.find(name, pos)) != std::string_view::npos) {
        const bool starts = pos > 0 && std::isspace(static_cast<unsigned char>(tag[pos - 1]));
        const std::size_t q = pos + name.size();
        if (starts && q + 1 < tag.size() && tag[q] == '=' && tag[q + 1] == '"') {
            const std::size_t end = tag.find('"', q + 2);
            if (end == std::string_view::npos) return false;
            value = tag.substr(q + 2, end - q - 2);
            return true;
        }
        pos = q;
    }
    return false;
}

class PathParser {
  public:
    PathParser(std::string_view d, std::size_t offset, std::vector<Ring>& out)
        : d_(d), offset_(offset), out_(out) {}

    void parse_path() {
        char cmd = 0;
        while (skip_separators(), i_ < d_.size()) {
            const char c = d_[i_];
            if (std::isalpha(static_cast<unsigned char>(c))) {
                ++i_;
                if (c == 'Z') {
                    close();
                    cmd = 0;
                    continue;
                }
                if (c != 'M' && c != 'L' && c != 'H' && c != 'V')
                    throw bad(offset_, std::string("path command '") + c +
                                           "' is not supported (absolute M L H V Z only)");
                cmd = c;
                if (c == 'M') {
                    if (!current_.empty()) throw bad(offset_, "subpath not closed with Z");
                    const std::int64_t x = number(), y = -number();
                    current_.push_back({x, y});
                    cmd = 'L';  // further pairs are implicit line-tos
                }
                continue;
            }
            if (cmd == 0 || current_.empty())
                throw bad(offset_, "path data must start each subpath with M");
            PointNm p = current_.back();
            if (cmd == 'L') {
                p.x = number();
                p.y = -number();
            } else if (cmd == 'H') {
                p.x = number();
            } else {
                p.y = -number();
            }
            current_.push_back(p);
        }
        if (!current_.empty()) throw bad(offset_, "subpath not closed with Z");
    }

    void parse_points() {
        while (skip_separators(), i_ < d_.size()) {
            const std::int64_t x = number(), y = -number();
            current_.push_back({x, y});
        }
        close();
    }

  private:
    void skip_separators() {
        while (i_ < d_.size() &&
               (d_[i_] == ',' || std::isspace(static_cast<unsigned char>(d_[i_]))))
            ++i_;
    }

    std::int64_t number() {
        skip_separators();
        const std::size_t start = i_;
        if (i_ < d_.size() && (d_[i_] == '-' || d_[i_] == '+')) ++i_;
        while (i_ < d_.size() &&
               (std::isdigit(static_cast<unsigned char>(d_[i_])) || d_[i_] == '.'))
            ++i_;
        if (i_ == start) throw bad(offset_, "expected a number in path data");
        return parse_scaled(d_.substr(start, i_ - start), kMicrometreDigits, "svg coordinate");
    }

    void close() {
        if (current_.size() >= 2 && current_.front() == current_.back()) current_.pop_back();
        if (current_.size() < 3) throw bad(offset_, "a closed subpath needs 3 or more vertices");
        out_.push_back(std::move(current_));
        current_.clear();
    }

    std::string_view d_;
    std::size_t offset_;
    std::vector<Ring>& out_;
    std::size_t i_ = 0;
    Ring current_;
};

// Micrometres in one `unit` of an SVG length ("mm", "um", "cm", "in", "pt", "pc", "px"); 0 for
// an unknown unit.
double um_per(std::string_view unit) {
    if (unit == "mm") return 1000.0;
    if (unit == "um") return 1.0;
    if (unit == "cm") return 10000.0;
    if (unit == "in") return 25400.0;
    if (unit == "pt") return 25400.0 / 72.0;
    if (unit == "pc") return 25400.0 / 6.0;
    if (unit == "px" || unit.empty()) return 25400.0 / 96.0;
    return 0.0;
}

// A length attribute in micrometres ("14.08mm"); NaN when malformed.
double length_um(std::string_view v) {
    std::size_t i = 0;
    while (i < v.size() && (std::isdigit(static_cast<unsigned char>(v[i])) || v[i] == '.' ||
                            v[i] == '-' || v[i] == '+' || v[i] == 'e' || v[i] == 'E'))
        ++i;
    const double per = um_per(v.substr(i));
    if (i == 0 || per == 0.0) return std::nan("");
    try {
        return std::stod(std::string(v.substr(0, i))) * per;
    } catch (...) {
        return std::nan("");
    }
}

// 1 user unit must be 1 um: width / viewBox width (and height) = 1 um. Without width and height
// the user unit is taken as 1 um (pinmask's convention, nothing scales it).
void check_scale(std::string_view root, std::size_t at) {
    std::string_view w, h, vb;
    const bool has_w = attribute(root, "width", w), has_h = attribute(root, "height", h);
    if (!has_w && !has_h) return;
    if (!has_w || !has_h || !attribute(root, "viewBox", vb))
        throw bad(at,
                  "<svg> with width/height but no viewBox: its user unit is a CSS pixel, "
                  "not a micrometre (pinmask reads viewBox user units of 1 um)");
    double box[4];
    std::string t(vb);
    for (char& c : t)
        if (c == ',') c = ' ';
    if (std::sscanf(t.c_str(), "%lf %lf %lf %lf", &box[0], &box[1], &box[2], &box[3]) != 4 ||
        !(box[2] > 0) || !(box[3] > 0))
        throw bad(at, "malformed viewBox '" + std::string(vb.substr(0, 40)) + "'");
    const double sx = length_um(w) / box[2], sy = length_um(h) / box[3];
    constexpr double kScaleTolerance = 1e-9;  // decimal rounding of the written sizes
    if (!(std::fabs(sx - 1) <= kScaleTolerance && std::fabs(sy - 1) <= kScaleTolerance))
        throw bad(at, "viewBox scaling is not supported: 1 user unit = " + std::to_string(sx) +
                          " x " + std::to_string(sy) +
                          " um (pinmask reads files whose user unit is 1 um)");
}

// The viewBox as a box in layout nanometres (y up), or nullopt when absent or malformed.
std::optional<BoxNm> viewbox_nm(std::string_view root) {
    std::string_view vb;
    if (!attribute(root, "viewBox", vb)) return std::nullopt;
    std::string t(vb);
    for (char& c : t)
        if (c == ',') c = ' ';
    std::istringstream in(t);
    std::string w[4];
    if (!(in >> w[0] >> w[1] >> w[2] >> w[3])) return std::nullopt;
    std::int64_t v[4];
    for (int i = 0; i < 4; ++i) v[i] = parse_scaled(w[i], kMicrometreDigits, "svg viewBox");
    return BoxNm{v[0], -(v[1] + v[3]), v[0] + v[2], -v[1]};
}

// The paint a renderer gives a drawn shape: black (the writer's "#000000"), white ("#ffffff",
// the clear rings of a film drawing), or anything else (refused where it is met).
enum class Paint { kBlack, kWhite };

std::optional<Paint> paint_of(std::string_view v) {
    if (v == "#000000" || v == "#000" || v == "black") return Paint::kBlack;
    if (v == "#ffffff" || v == "#fff" || v == "white") return Paint::kWhite;
    return std::nullopt;
}

// The attributes a renderer could draw differently with (visibility, opacity, stroke, clipping,
// classes and styles, paint) are refused by name unless they are what the writer writes: each
// element admits a fixed list, and values are checked. One tag's attributes, double-quoted.
struct TagAttributes {
    std::optional<Paint> fill;
};

TagAttributes check_attributes(std::string_view tag, const std::string& name, std::size_t pos) {
    static const char* const kSvg[] = {"xmlns",  "xmlns:xlink", "version", "width",
                                       "height", "viewBox",     "id"};
    static const char* const kShape[] = {"d", "points", "id", "fill", "stroke"};
    static const char* const kGroup[] = {"id", "fill", "stroke"};
    static const char* const kText[] = {"id"};
    auto allowed = [&](std::string_view a) {
        auto in = [&](const auto& list) {
            for (const char* x : list)
                if (a == x) return true;
            return false;
        };
        if (name == "svg") return in(kSvg);
        if (name == "path" || name == "polygon") return in(kShape);
        if (name == "g") return in(kGroup);
        return in(kText);
    };
    TagAttributes out;
    std::size_t i = 1 + name.size();
    while (true) {
        while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
        if (i >= tag.size() || tag[i] == '/' || tag[i] == '?') break;
        const std::size_t n0 = i;
        while (i < tag.size() && tag[i] != '=' && tag[i] != '/' &&
               !std::isspace(static_cast<unsigned char>(tag[i])))
            ++i;
        const std::string attr(tag.substr(n0, i - n0));
        while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
        if (i + 1 >= tag.size() || tag[i] != '=' || tag[i + 1] != '"')
            throw bad(pos + n0, "attribute '" + attr.substr(0, 30) + "' on <" + name +
                                    "> is not of the form name=\"value\" (pinmask reads "
                                    "double-quoted attributes)");
        const std::size_t v0 = i + 2, v1 = tag.find('"', v0);
        if (v1 == std::string_view::npos) throw bad(pos + n0, "attribute value is not closed");
        const std::string_view value = tag.substr(v0, v1 - v0);
        i = v1 + 1;
        if (!allowed(attr))
            throw bad(pos + n0, "attribute '" + attr.substr(0, 30) + "' on <" + name +
                                    "> is not supported: it can change what a renderer draws "
                                    "(pinmask reads the attributes its writer uses: d, points, "
                                    "fill, stroke=\"none\", id; svg: width, height, viewBox)");
        if (attr == "fill") {
            if (value == "none")
                throw bad(pos, "fill=\"none\" on <" + name +
                                   "> is not supported (an outline, not an area: pinmask reads "
                                   "filled shapes)");
            out.fill = paint_of(value);
            if (!out.fill)
                throw bad(pos, "fill=\"" + std::string(value.substr(0, 30)) + "\" on <" + name +
                                   "> is not supported (pinmask reads black shapes, and white "
                                   "ones on a film drawing's plate)");
        }
        if (attr == "stroke" && value != "none")
            throw bad(pos, "stroke=\"" + std::string(value.substr(0, 30)) + "\" on <" + name +
                               "> is not supported (a stroke widens the drawn shape)");
    }
    return out;
}

// Elements that change geometry and are not implemented are refused by name; elements that
// carry no geometry are allowed. Declarations (<!DOCTYPE>, <!ENTITY>, CDATA) and processing
// instructions other than the XML declaration are refused: a DOCTYPE can give attributes
// defaults (fill="none") and a stylesheet can restyle every shape. Returns the tag's attributes.
TagAttributes check_element(std::string_view text, std::size_t pos, std::size_t root) {
    if (text.substr(pos, 2) == "<!")
        throw bad(pos, "markup declaration " + std::string(text.substr(pos, 12)) +
                           " is not supported (a DOCTYPE can set attribute defaults and "
                           "entities)");
    if (text.substr(pos, 2) == "<?") {
        if (text.substr(pos, 6) != "<?xml " || pos > root)
            throw bad(pos, "processing instruction " + std::string(text.substr(pos, 20)) +
                               " is not supported (a stylesheet can restyle the drawing)");
        return {};
    }
    if (text.substr(pos, 2) == "</") return {};
    std::size_t end = pos + 1;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) ||
                                 text[end] == ':' || text[end] == '-' || text[end] == '_'))
        ++end;
    const std::string name(text.substr(pos + 1, end - pos - 1));
    static const char* const kAllowed[] = {"svg",      "g",     "path", "polygon",
                                           "metadata", "title", "desc", "defs"};
    bool ok = false;
    for (const char* a : kAllowed) ok = ok || name == a;
    if (!ok)
        throw bad(pos, "element <" + name.substr(0, 30) +
                           "> is not supported (pinmask reads filled <path> and <polygon> "
                           "elements only)");
    if (name == "svg" && pos != root)
        throw bad(pos, "a nested <svg> is not supported (its viewport can scale and clip)");
    if (name == "defs") throw bad(pos, "<defs> (reusable content) is not supported");
    const std::size_t close = text.find('>', pos);
    const std::string_view tag =
        text.substr(pos, (close == std::string_view::npos ? text.size() : close) - pos);
    return check_attributes(tag, name, pos);
}

}  // namespace

FileGeometry read_svg(std::string_view text) {
    FileGeometry g;
    const std::size_t root = text.find("<svg");
    if (root == std::string_view::npos) throw bad(0, "no <svg> element: not an SVG document");
    std::size_t end = text.find_last_not_of(" \t\r\n");
    if (end == std::string_view::npos || text.substr(0, end + 1).ends_with("</svg>") == false)
        throw bad(text.size(), "the document does not end with </svg> (truncated?)");
    const std::size_t meta = text.find("<metadata>");
    if (meta != std::string_view::npos) {
        const std::size_t stop = text.find("</metadata>", meta);
        if (stop == std::string_view::npos) throw bad(meta, "<metadata> is not closed");
        g.info = parse_info(text.substr(meta + 10, stop - meta - 10));
    }
    // The prolog: the XML declaration and comments only (a DOCTYPE or a stylesheet there would
    // restyle the drawing).
    for (std::size_t pos = 0; (pos = text.find('<', pos)) < root; ++pos) {
        if (text.substr(pos, 4) == "<!--") {
            constexpr char kCommentEnd[] = {'-', '-', '>', '\0'};
            const std::size_t stop = text.find(kCommentEnd, pos);
            if (stop == std::string_view::npos) throw bad(pos, "comment is not closed");
            pos = stop + 2;
            continue;
        }
        if (text.substr(pos, 6) == "<?xml " && pos == 0) continue;
        check_element(text, pos, root);
        throw bad(pos, "unexpected markup before <svg>");
    }
    const std::string_view root_tag = text.substr(root, text.find('>', root) - root);
    check_scale(root_tag, root);
    // A film drawing's opaque plate (export/formats/svg_writer kSvgFilmGroup): read, checked, left
    // out.
    std::vector<Ring> plate;
    bool in_plate = false;
    // Fills of the open groups (the root's: none given).
    std::vector<std::optional<Paint>> group_fill{std::nullopt};
    const auto draw_it = g.info.find("draw");
    const auto tone_it = g.info.find("tone");
    const bool film_clear = draw_it != g.info.end() && draw_it->second == "film" &&
                            tone_it != g.info.end() && tone_it->second == "clear";
    TimeLimitPoll poll_time("reading the SVG file");
    for (std::size_t pos = root; (pos = text.find('<', pos)) != std::string_view::npos; ++pos) {
        poll_time();
        if (text.substr(pos, 4) == "<!--") {  // comments may contain anything
            // The comment's end, "-" "-" ">", as characters: no string literal here starts
            // like a command-line flag (the libraries are checked for those).
            constexpr char kCommentEnd[] = {'-', '-', '>', '\0'};
            const std::size_t stop = text.find(kCommentEnd, pos);
            if (stop == std::string_view::npos) throw bad(pos, "comment is not closed");
            pos = stop + 2;
            continue;
        }
        if (meta != std::string_view::npos && pos > meta && pos < text.find("</metadata>", meta))
            continue;
        const TagAttributes attrs = check_element(text, pos, root);
        // <title>, <desc> and <metadata> hold content a renderer never draws: a shape inside
        // <title> or <desc> would be read as a pinhole no drawing shows, so markup there is
        // refused; every <metadata> (other tools put RDF markup there) is skipped whole, as a
        // renderer skips it.
        bool skipped = false;
        for (const std::string_view holder : {"title", "desc", "metadata"}) {
            const std::string open = "<" + std::string(holder);
            if (text.substr(pos, open.size()) != open || pos + open.size() >= text.size()) continue;
            const char after = text[pos + open.size()];
            if (after != '>' && after != '/' && !std::isspace(static_cast<unsigned char>(after)))
                continue;
            const std::size_t tag_end = text.find('>', pos);
            if (tag_end == std::string_view::npos) throw bad(pos, "element is not closed");
            if (text[tag_end - 1] == '/') break;  // <desc/>: empty
            const std::string close = "</" + std::string(holder) + ">";
            const std::size_t stop = text.find(close, tag_end);
            if (stop == std::string_view::npos)
                throw bad(pos, "<" + std::string(holder) + "> is not closed");
            if (holder != "metadata" &&
                text.substr(tag_end + 1, stop - tag_end - 1).find('<') != std::string_view::npos)
                throw bad(pos, "markup inside <" + std::string(holder) +
                                   "> is not supported: a renderer draws nothing inside it, so "
                                   "a shape there is no part of the drawing");
            pos = stop + close.size() - 1;
            skipped = true;
            break;
        }
        if (skipped) continue;
        const bool is_group = text.substr(pos, 3) == "<g " || text.substr(pos, 3) == "<g>";
        if (is_group) {
            std::string_view id;
            const std::string_view tag = text.substr(pos, text.find('>', pos) - pos);
            in_plate = attribute(tag, "id", id) && id == kSvgFilmGroup;
            const bool self_closing = !tag.empty() && tag.back() == '/';
            if (!self_closing) group_fill.push_back(attrs.fill ? attrs.fill : group_fill.back());
        } else if (text.substr(pos, 4) == "</g>") {
            in_plate = false;
            if (group_fill.size() > 1) group_fill.pop_back();
        }
        const bool is_path = text.substr(pos, 6) == "<path " || text.substr(pos, 6) == "<path\n";
        const bool is_polygon = text.substr(pos, 9) == "<polygon ";
        if (!is_path && !is_polygon) continue;
        // The paint it is drawn with (its own fill, else its group's, else SVG's default, black)
        // against the drawing's: black shapes, or white clear rings on a film drawing's plate.
        const Paint paint = attrs.fill ? *attrs.fill : group_fill.back().value_or(Paint::kBlack);
        const Paint expected = in_plate || !film_clear ? Paint::kBlack : Paint::kWhite;
        if (paint != expected)
            throw bad(pos, std::string("a ") + (paint == Paint::kWhite ? "white" : "black") +
                               " shape where the drawing's shapes are " +
                               (expected == Paint::kWhite ? "white (the clear rings of a film "
                                                            "drawing)"
                                                          : "black") +
                               ": a renderer would not draw it as part of the mask");
        const std::size_t close = text.find('>', pos);
        if (close == std::string_view::npos) throw bad(pos, "element is not closed");
        const std::string_view tag = text.substr(pos, close - pos);
        std::string_view data;
        if (!attribute(tag, is_path ? "d" : "points", data))
            throw bad(pos, is_path ? "<path> without a d attribute" : "<polygon> without points");
        PathParser parser(data, pos, in_plate ? plate : g.rings);
        if (is_path)
            parser.parse_path();
        else
            parser.parse_points();
        pos = close;
    }
    if (!plate.empty()) {
        const std::optional<BoxNm> vb = viewbox_nm(root_tag);
        if (plate.size() != 1 || !vb || canonical_rings(plate) != canonical_rings({box_ring(*vb)}))
            throw bad(root, std::string("group ") + kSvgFilmGroup +
                                " (the opaque plate of a film drawing) must hold one rectangle, "
                                "the viewBox");
        const auto draw = g.info.find("draw");
        if (draw == g.info.end() || draw->second != "film")
            throw bad(root, std::string("group ") + kSvgFilmGroup +
                                " in a drawing whose metadata does not say draw=film");
    } else if (auto d = g.info.find("draw");
               d != g.info.end() && d->second == "film" && g.info["tone"] == "clear") {
        throw bad(root, "a clear-tone film drawing (draw=film) without its opaque plate group");
    }
    return g;
}

}  // namespace pinmask
