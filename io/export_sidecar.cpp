#include "io/export_sidecar.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "core/errors/error.hpp"
#include "core/files/input_file.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {
namespace {

using nlohmann::json;

json box(const std::array<std::int64_t, 4>& b) { return json::array({b[0], b[1], b[2], b[3]}); }

InvalidInput bad(const std::filesystem::path& p, const std::string& key, const std::string& rule) {
    return InvalidInput(p.string() + ": " + key + ": " + rule);
}

// A sidecar is a few kilobytes (its label lines and file list); anything near this is not one.
constexpr std::uintmax_t kMaxSidecarBytes = 4u << 20;

// The value at key, of type T, checked before it is converted: a number that does not fit T (a
// float for an integer, 1e300 for an int, a negative count) is refused, never cast.
template <class T>
T get(const json& j, const char* key, const std::filesystem::path& p, const std::string& where) {
    if (!j.is_object()) throw bad(p, where, "must be an object");
    const auto it = j.find(key);
    if (it == j.end()) throw bad(p, where + "." + key, "is missing");
    const json& v = *it;
    const std::string at = where + "." + key;
    if constexpr (std::is_same_v<T, bool>) {
        if (!v.is_boolean()) throw bad(p, at, "must be true or false");
        return v.get<bool>();
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (!v.is_string()) throw bad(p, at, "must be a string");
        return v.get<std::string>();
    } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
        if (!v.is_array()) throw bad(p, at, "must be an array of strings");
        std::vector<std::string> out;
        for (const json& e : v) {
            if (!e.is_string()) throw bad(p, at, "must be an array of strings");
            out.push_back(e.get<std::string>());
        }
        return out;
    } else if constexpr (std::is_floating_point_v<T>) {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            throw bad(p, at, "must be a finite number");
        return v.get<double>();
    } else {
        static_assert(std::is_integral_v<T>);
        if (v.is_number_unsigned()) {
            const auto u = v.get<std::uint64_t>();
            if (u > static_cast<std::uint64_t>(std::numeric_limits<T>::max()))
                throw bad(p, at, "is out of range");
            return static_cast<T>(u);
        }
        if (!v.is_number_integer()) throw bad(p, at, "must be an integer");
        const auto i = v.get<std::int64_t>();
        if (i < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
            (std::is_signed_v<T> && i > static_cast<std::int64_t>(std::numeric_limits<T>::max())))
            throw bad(p, at, "is out of range");
        return static_cast<T>(i);
    }
}

template <class T>
T get_or(const json& j, const char* key, T fallback, const std::filesystem::path& p,
         const std::string& where) {
    return j.contains(key) ? get<T>(j, key, p, where) : fallback;
}

}  // namespace

std::string export_sidecar_text(const ExportSidecar& s) {
    json files = json::array();
    for (const ExportSidecarFile& f : s.files) {
        json e = {{"name", f.name},   {"format", f.format},   {"units", f.units},
                  {"bytes", f.bytes}, {"fnv1a64", f.fnv1a64}, {"verification", f.verification}};
        if (!f.detail.empty()) e["detail"] = f.detail;
        files.push_back(e);
    }
    json side = {
        {"format", "pinmask-export"},
        {"version", 1},
        {"mask",
         {{"path", s.mask_path},
          {"geometry_hash", s.geometry_hash},
          {"n", s.n},
          {"tiles", {s.tiles_rows, s.tiles_cols}},
          {"pinholes", s.pinholes},
          {"pinhole_m", s.pinhole_m}}},
        {"geometry",
         {{"units", "nm (integers), origin at the mask centre, y up"},
          {"orientation", "mask row 0 at the top (+y), column 0 at the left (-x)"},
          {"unit", s.unit},
          {"grid_nm", s.grid_nm},
          {"tone", s.tone},
          {"drawn", s.tone == "clear" ? "clear areas" : "opaque areas"},
          {"mirrored", s.mirrored},
          {"emulsion", s.mirrored ? "down" : "up"},
          {"shape", s.shape},
          {"sides", s.sides},
          {"drawn_sides", s.drawn_sides},
          {"hole_side_m", s.hole_side_m},
          {"chord_tolerance_m", s.chord_tolerance_m > 0 ? json(s.chord_tolerance_m) : "auto"},
          {"frame_m", s.frame_m},
          {"marks", s.marks},
          {"label", s.label},
          {"max_vertices", s.max_vertices},
          {"draw", s.draw},
          {"svg_draw", s.svg_draw},
          {"circles", s.circles},
          {"hierarchy", s.hierarchy},
          {"kerf_m", s.kerf_m},
          {"png_dpi", s.png_dpi},
          {"pdf_margin_m", s.pdf_margin_m},
          {"active_area_nm", box(s.active_area_nm)},
          {"extent_nm", box(s.extent_nm)},
          {"polygons", s.polygons},
          {"annotations", s.annotations}}},
        {"drc", {{"vendor", s.vendor}, {"clean", s.drc_clean}, {"counts", s.drc_counts}}},
        {"files", files},
        {"psf", s.psf_absent},
        {"notes", s.notes}};
    if (!s.rules_name.empty())
        side["drc"]["rules"] = {{"name", s.rules_name},
                                {"min_feature_nm", s.rules_min_feature_nm},
                                {"min_space_nm", s.rules_min_space_nm},
                                {"max_vertices", s.rules_max_vertices}};
    if (!s.psf_files.empty())
        side["psf"] = {{"files", s.psf_files},
                       {"kernel", s.psf_kernel},
                       {"pixels_per_cell", s.psf_pixels_per_cell},
                       {"size_px", {s.psf_rows, s.psf_cols}}};
    return side.dump(2) + "\n";
}

ExportSidecar read_export_sidecar(const std::filesystem::path& p) {
    if (const auto problem = input_file_problem(p)) throw bad(p, "(root)", *problem);
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(p, ec);
    if (!ec && bytes > kMaxSidecarBytes)
        throw bad(p, "(root)", std::to_string(bytes) + " bytes is too large for an export sidecar");
    std::ifstream in(p, std::ios::binary);
    if (!in) throw RuntimeFailure("cannot read " + p.string());
    std::ostringstream text;
    text << in.rdbuf();
    json j;
    try {
        j = json_strict::parse_strict(text.str());  // nesting bounded, repeated keys refused
    } catch (const json::exception& e) {
        throw bad(p, "(root)", std::string("is not JSON: ") + json_strict::json_error_words(e));
    }
    if (!j.is_object() || !j.contains("format") || !j["format"].is_string() ||
        j["format"].get<std::string>() != "pinmask-export")
        throw bad(p, "format", "must be \"pinmask-export\"");
    if (get<int>(j, "version", p, "(root)") != 1) throw bad(p, "version", "must be 1");
    ExportSidecar s;
    if (!j.contains("mask") || !j["mask"].is_object()) throw bad(p, "mask", "is missing");
    if (!j.contains("geometry") || !j["geometry"].is_object())
        throw bad(p, "geometry", "is missing");
    const json& m = j["mask"];
    s.mask_path = get<std::string>(m, "path", p, "mask");
    s.geometry_hash = get<std::string>(m, "geometry_hash", p, "mask");
    const json& g = j["geometry"];
    const std::string w = "geometry";
    s.unit = get_or<std::string>(g, "unit", "um", p, w);
    s.grid_nm = get<std::int64_t>(g, "grid_nm", p, w);
    if (s.grid_nm < 1) throw bad(p, "geometry.grid_nm", "must be at least 1 nm");
    s.tone = get<std::string>(g, "tone", p, w);
    s.mirrored = get<bool>(g, "mirrored", p, w);
    s.shape = get<std::string>(g, "shape", p, w);
    s.drawn_sides = get<int>(g, "sides", p, w);
    s.sides = s.drawn_sides;
    s.hole_side_m = get<double>(g, "hole_side_m", p, w);
    if (g.contains("chord_tolerance_m") && g["chord_tolerance_m"].is_number())
        s.chord_tolerance_m = g["chord_tolerance_m"].get<double>();
    s.frame_m = get<double>(g, "frame_m", p, w);
    s.marks = get<bool>(g, "marks", p, w);
    s.label = get<std::vector<std::string>>(g, "label", p, w);
    s.max_vertices = get<std::size_t>(g, "max_vertices", p, w);
    s.draw = get_or<std::string>(g, "draw", "film", p, w);
    s.svg_draw = get_or<std::string>(g, "svg_draw", "polygons", p, w);
    s.circles = get_or<std::string>(g, "circles", "polygon", p, w);
    s.hierarchy = get_or<std::string>(g, "hierarchy", "flat", p, w);
    s.kerf_m = get_or<double>(g, "kerf_m", 0.0, p, w);
    s.png_dpi = get_or<double>(g, "png_dpi", 0.0, p, w);
    s.pdf_margin_m = get_or<double>(g, "pdf_margin_m", 10e-3, p, w);
    if (!(s.png_dpi >= 0 && s.png_dpi <= 1e6))
        throw bad(p, "geometry.png_dpi", "must be in 0..1000000");
    if (!(s.pdf_margin_m >= 0 && s.pdf_margin_m <= 1))
        throw bad(p, "geometry.pdf_margin_m", "must be in 0..1 m");
    if (j.contains("drc") && j["drc"].is_object()) {
        const json& d = j["drc"];
        s.vendor = get_or<std::string>(d, "vendor", "none", p, "drc");
        if (d.contains("rules")) {
            const json& r = d["rules"];
            s.rules_name = get<std::string>(r, "name", p, "drc.rules");
            s.rules_min_feature_nm = get<std::int64_t>(r, "min_feature_nm", p, "drc.rules");
            s.rules_min_space_nm = get<std::int64_t>(r, "min_space_nm", p, "drc.rules");
            s.rules_max_vertices = get<std::size_t>(r, "max_vertices", p, "drc.rules");
            constexpr std::int64_t kMaxRuleNm = std::int64_t{1} << 31;
            if (s.rules_name.empty()) throw bad(p, "drc.rules.name", "must not be empty");
            if (s.rules_min_feature_nm < 0 || s.rules_min_feature_nm > kMaxRuleNm)
                throw bad(p, "drc.rules.min_feature_nm", "must be between 0 and 2^31");
            if (s.rules_min_space_nm < 1 || s.rules_min_space_nm > kMaxRuleNm)
                throw bad(p, "drc.rules.min_space_nm", "must be between 1 and 2^31");
            if (s.rules_max_vertices < 3) throw bad(p, "drc.rules.max_vertices", "must be >= 3");
        }
    }
    if (j.contains("files") && j["files"].is_array())
        for (const json& f : j["files"]) {
            if (!f.is_object()) throw bad(p, "files[]", "must be an object");
            ExportSidecarFile e;
            e.name = get<std::string>(f, "name", p, "files[]");
            e.format = get<std::string>(f, "format", p, "files[]");
            e.fnv1a64 = get_or<std::string>(f, "fnv1a64", "", p, "files[]");
            // What identifies the film (the layer check compares, export/pipeline/film_identity).
            e.detail = get_or<std::string>(f, "detail", "", p, "files[]");
            s.files.push_back(e);
        }
    return s;
}

std::filesystem::path sidecar_path_for(const std::filesystem::path& file) {
    return file.parent_path() / (file.stem().string() + ".export.json");
}

}  // namespace pinmask::io
