// `pinmask check`: the design-rule check (export/drc) of a mask file, via the layout the export
// builds from it, or of a fabrication file read back (GDSII, DXF, Gerber, SVG), optionally
// compared by exact XOR area with the layout of the mask it was made from.
// Exit codes: 0 clean, 1 violations (or an XOR mismatch), 2 bad input.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "cli/command.hpp"
#include "io/mask_json.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "export/drc.hpp"
#include "export/geometry.hpp"
#include "export/read_any.hpp"
#include "export/rings.hpp"
#include "export/vendor_rules.hpp"
#include "export/xor_area.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

struct CheckOptions {
    std::string input;
    std::string mask;  // design of a fabrication file
    std::string vendor = "film";
    std::optional<std::string> min_gap, min_feature, min_spacing;
    std::optional<std::size_t> max_vertices;
    std::size_t list = 20;
    double max_xor_um2 = 0.0;
    // Layout options of the design the file is compared with (as given to `pinmask export`).
    std::string shape = "square";
    int sides = 8;
    std::optional<std::string> hole_side, frame, chord_tol;
    bool json = false;
};

// A mask file is JSON: a .json name or a first non-blank byte '{'.
bool is_mask_file(const fs::path& path) {
    if (path.extension() == ".json") return true;
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    }
    return in && c == '{';
}

std::int64_t length_nm(const std::string& text, const char* flag, std::int64_t min_nm) {
    const double nm = std::round(parse_length_m(text, flag) * 1e9);
    if (!(nm >= double(min_nm)) || nm > 1e12) {
        throw invalid_field(flag, text,
                            "must be between " + std::to_string(min_nm) + " nm and 1e12 nm (1 km)");
    }
    return static_cast<std::int64_t>(nm);
}

DrcRules resolve_rules(const CheckOptions& o, DrcRules rules) {
    if (o.min_gap) rules.min_gap_nm = length_nm(*o.min_gap, "--min-gap", 1);
    if (o.min_feature) rules.min_feature_nm = length_nm(*o.min_feature, "--min-feature", 0);
    if (o.min_spacing) {
        rules.min_center_spacing_nm = double(length_nm(*o.min_spacing, "--min-spacing", 0));
    }
    if (o.max_vertices) rules.max_vertices = *o.max_vertices;
    if (o.list < 1) throw invalid_field("--list", std::to_string(o.list), "must be >= 1");
    rules.max_reported_per_rule = o.list;
    return rules;
}

LayoutOptions design_options(const CheckOptions& o, const FileGeometry* file) {
    LayoutOptions lo;
    lo.shape = parse_hole_shape(o.shape, "--shape");
    lo.polygon_sides = o.sides;
    if (o.hole_side) lo.hole_side_m = parse_length_m(*o.hole_side, "--hole-side");
    if (o.frame) lo.frame_m = parse_length_m(*o.frame, "--frame");
    if (o.chord_tol) lo.chord_tolerance_m = parse_length_m(*o.chord_tol, "--chord-tol");
    if (file) {  // tone, mirroring and grid as the file declares them
        const auto& info = file->info;
        if (auto it = info.find("tone"); it != info.end()) lo.tone = parse_tone(it->second, "tone");
        if (auto it = info.find("mirrored"); it != info.end()) lo.mirror = it->second == "yes";
        if (auto it = info.find("grid_nm"); it != info.end()) {
            lo.grid_m = parse_number(it->second, "grid_nm") * 1e-9;
        }
    }
    return lo;
}

bool box_inside(const BoxNm& inner, const BoxNm& outer) {
    return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x1 <= outer.x1 &&
           inner.y1 <= outer.y1;
}

struct Comparison {
    double xor_um2 = 0;
    double max_um2 = 0;
    std::string file_hash, mask_hash;
    bool ok() const { return xor_um2 <= max_um2 && (file_hash.empty() || file_hash == mask_hash); }
};

struct Checked {
    std::string kind;  // "mask" or the file format
    Layout layout;
    DrcRules rules;
    std::optional<Comparison> comparison;
    std::string note;
};

// A fabrication file as a layout: with the design, rings inside the design's outline are the
// polygons and the rest annotations; without it every ring is a polygon.
Checked check_file(const CheckOptions& o, const VendorRules& vendor) {
    Checked c;
    const FileGeometry file = read_fabrication_file(o.input);
    c.kind = fs::path(o.input).extension().string().substr(1);
    Layout& l = c.layout;
    const auto tone = file.info.find("tone");
    l.tone = tone == file.info.end() ? Tone::kClear : parse_tone(tone->second, "tone");
    l.extent = bounding_box(file.rings);
    if (o.mask.empty()) {
        l.polygons = file.rings;
        l.active_area = l.extent;
        DrcRules rules;
        rules.min_gap_nm = vendor.min_gap_nm;
        rules.min_feature_nm = vendor.min_feature_nm;
        rules.max_vertices = vendor.max_vertices;
        c.rules = resolve_rules(o, rules);
        c.note =
            "no --mask: all rings are checked as polygons; centre spacing only with "
            "--min-spacing";
        return c;
    }
    const Mask mask = io::read_mask_file(o.mask, {.allow_spacing_violations = true});
    const Layout design = make_layout(mask, design_options(o, &file));
    const BoxNm outline = bounding_box(design.polygons);
    for (const Ring& r : file.rings) {
        (box_inside(bounding_box({r}), outline) ? l.polygons : l.annotations).push_back(r);
    }
    l.active_area = design.active_area;
    l.extent = box_union(l.extent, design.extent);
    c.rules = resolve_rules(o, rules_for_mask(mask, vendor));
    Comparison cmp;
    cmp.xor_um2 = xor_area_nm2(l.polygons, design.polygons) * 1e-6;
    cmp.max_um2 = o.max_xor_um2;
    cmp.mask_hash = geometry_hash(mask);
    if (auto it = file.info.find("hash"); it != file.info.end()) cmp.file_hash = it->second;
    c.comparison = cmp;
    return c;
}

Checked check_mask(const CheckOptions& o, const VendorRules& vendor) {
    if (!o.mask.empty()) throw invalid_field("--mask", o.mask, "only used with a fabrication file");
    Checked c;
    c.kind = "mask";
    const Mask mask = io::read_mask_file(o.input, {.allow_spacing_violations = true});
    c.layout = make_layout(mask, design_options(o, nullptr));
    c.rules = resolve_rules(o, rules_for_mask(mask, vendor));
    return c;
}

std::string um_text(double nm) {
    if (std::isinf(nm)) return "none below the limit";
    std::ostringstream s;
    s << nm * 1e-3 << " um";
    return s.str();
}

nlohmann::ordered_json finite_or_null(double nm) {
    return std::isfinite(nm) ? nlohmann::ordered_json(nm * 1e-3) : nlohmann::ordered_json();
}

nlohmann::ordered_json index_or_null(std::size_t i) {
    return i == kNoPolygon ? nlohmann::ordered_json() : nlohmann::ordered_json(i);
}

void print_json(const CheckOptions& o, const Checked& c, const DrcReport& r, bool clean) {
    nlohmann::ordered_json v = nlohmann::ordered_json::array();
    for (const DrcViolation& x : r.violations) {
        v.push_back({{"rule", x.rule},
                     {"message", x.message},
                     {"x_um", double(x.where.x) * 1e-3},
                     {"y_um", double(x.where.y) * 1e-3},
                     {"polygon_a", index_or_null(x.polygon_a)},
                     {"polygon_b", index_or_null(x.polygon_b)},
                     {"value", x.value},
                     {"limit", x.limit},
                     {"unit", x.rule == "vertices" || x.rule == "ring" ? "vertices" : "nm"}});
    }
    nlohmann::ordered_json j = {
        {"clean", clean},
        {"input", o.input},
        {"kind", c.kind},
        {"vendor", o.vendor},
        {"tone", tone_name(c.layout.tone)},
        {"polygons", c.layout.polygons.size()},
        {"annotations", c.layout.annotations.size()},
        {"rules",
         {{"min_center_spacing_um", c.rules.min_center_spacing_nm * 1e-3},
          {"min_gap_um", double(c.rules.min_gap_nm) * 1e-3},
          {"min_feature_um", double(c.rules.min_feature_nm) * 1e-3},
          {"max_vertices", c.rules.max_vertices}}},
        {"measured",
         {{"min_center_spacing_um", finite_or_null(r.measured.min_center_spacing_nm)},
          {"min_gap_um", finite_or_null(r.measured.min_gap_nm)},
          {"min_feature_um", finite_or_null(r.measured.min_feature_nm)}}},
        {"counts", r.counts},
        {"truncated", r.truncated},
        {"violations", v}};
    if (c.comparison) {
        j["comparison"] = {{"mask", o.mask},
                           {"xor_area_um2", c.comparison->xor_um2},
                           {"max_xor_area_um2", c.comparison->max_um2},
                           {"file_hash", c.comparison->file_hash},
                           {"mask_hash", c.comparison->mask_hash},
                           {"ok", c.comparison->ok()}};
    }
    std::cout << j.dump() << "\n";
}

void print_text(const CheckOptions& o, const Checked& c, const DrcReport& r, bool clean,
                const VendorRules& vendor) {
    std::ostringstream s;
    const DrcRules& ru = c.rules;
    s << "check " << o.input << " (" << c.kind << "; vendor " << vendor.name << ": "
      << vendor.description << ")\n";
    s << "  polygons    " << c.layout.polygons.size() << " + " << c.layout.annotations.size()
      << " annotations, tone " << tone_name(c.layout.tone) << "\n";
    const bool spacing = ru.min_center_spacing_nm > 0;
    s << "  rules       centre spacing "
      << (spacing ? ">= " + um_text(ru.min_center_spacing_nm) : "not checked")
      << ", gap >= " << um_text(double(ru.min_gap_nm))
      << ", feature >= " << um_text(double(ru.min_feature_nm)) << ", <= " << ru.max_vertices
      << " vertices\n";
    s << "  measured    centre spacing "
      << (spacing ? um_text(r.measured.min_center_spacing_nm) : "not checked") << ", gap "
      << um_text(r.measured.min_gap_nm) << ", feature " << um_text(r.measured.min_feature_nm)
      << "\n";
    if (c.comparison) {
        const Comparison& k = *c.comparison;
        s << "  vs design   " << o.mask << ": XOR area " << k.xor_um2 << " um^2 (max " << k.max_um2
          << "), hash " << (k.file_hash.empty() ? "not in file" : k.file_hash)
          << (k.file_hash.empty() || k.file_hash == k.mask_hash ? "" : " != " + k.mask_hash)
          << (k.ok() ? "" : "  MISMATCH") << "\n";
    }
    if (!c.note.empty()) s << "  note        " << c.note << "\n";
    if (r.clean()) {
        s << "  violations  none\n";
    } else {
        std::size_t total = 0;
        std::string parts;
        for (const auto& [rule, n] : r.counts) {
            total += n;
            parts += (parts.empty() ? "" : ", ") + rule + " " + std::to_string(n);
        }
        s << "  violations  " << total << " (" << parts << ")"
          << (r.truncated ? ", scan stopped early" : "") << "; at most " << o.list
          << " listed per rule\n";
        for (const DrcViolation& v : r.violations) {
            s << "    " << v.rule << ": " << v.message << "\n";
        }
    }
    s << "  result      " << (clean ? "clean" : "FAILED") << "\n";
    std::cout << s.str();
}

void run(const CheckOptions& o) {
    if (!fs::is_regular_file(o.input)) {
        throw invalid_field("input", o.input, "must be an existing mask or fabrication file");
    }
    if (!std::isfinite(o.max_xor_um2) || o.max_xor_um2 < 0) {
        throw invalid_field("--max-xor-um2", std::to_string(o.max_xor_um2),
                            "must be finite and >= 0");
    }
    const VendorRules vendor = vendor_rules(o.vendor);
    const Checked c = is_mask_file(o.input) ? check_mask(o, vendor) : check_file(o, vendor);
    const DrcReport r = run_drc(c.layout, c.rules);
    const bool clean = r.clean() && (!c.comparison || c.comparison->ok());
    if (o.json) {
        print_json(o, c, r, clean);
    } else {
        print_text(o, c, r, clean, vendor);
    }
    if (!clean) set_exit_code(1);
}

constexpr const char* kFooter =
    "A mask file is checked on the layout `pinmask export` builds from it (square pinholes of "
    "the full cell unless --shape/--hole-side say otherwise; clear tone). A fabrication file "
    "(.gds .dxf .gbr .svg) is read back in nanometres; with --mask its rings inside the "
    "design's outline are the pinholes (the rest marks and label), the spacing rule comes from "
    "the mask, and those rings must match the design's polygons: XOR area <= --max-xor-um2, "
    "and the file's geometry hash must be the mask's. Give --shape/--sides/--hole-side/--frame/"
    "--chord-tol as they were given to export; tone, mirroring and grid are read from the "
    "file.\n"
    "Rules (exact, integer nm): ring, vertices, self_intersection, orientation (CCW), area, "
    "feature (width between facing edges), gap (edge to edge, also notches), touching, overlap, "
    "spacing (pinhole centroids, on the plane of the tiled mask). Dark tone: the clear regions "
    "(holes of the union of the opaque pieces) take the pinhole rules.\n"
    "Exit codes: 0 clean, 1 violations or a mismatch with the design, 2 bad input.\n"
    "Example: pinmask check m.mask.json --vendor film && pinmask check m.gds --mask m.mask.json";

void setup(CLI::App& app) {
    auto o = std::make_shared<CheckOptions>();
    auto* cmd = app.add_subcommand(
        "check", "Design-rule check of a mask file or an exported fabrication file.");
    cmd->footer(kFooter);
    cmd->add_option("input", o->input, "A *.mask.json, or a .gds/.dxf/.gbr/.svg file")->required();
    cmd->add_option("--vendor", o->vendor,
                    "Process limits: film (features and gaps >= 16 um, 20000 dpi plotter), chrome "
                    "(>= 1 um), none (polygons must only not touch); all: <= 199 vertices")
        ->capture_default_str();
    cmd->add_option("--min-gap", o->min_gap,
                    "Override the vendor's minimum gap between polygons (length, e.g. 16um; "
                    ">= 1 nm)");
    cmd->add_option("--min-feature", o->min_feature,
                    "Override the vendor's minimum feature width (length; 0 disables)");
    cmd->add_option("--min-spacing", o->min_spacing,
                    "Override the minimum pinhole centre spacing (length; default: the mask's "
                    "min_spacing_cells x pinhole side, none without a mask)");
    cmd->add_option("--max-vertices", o->max_vertices,
                    "Override the vertex limit per polygon (GDSII: 199 friendly, 8190 hard)");
    cmd->add_option("--mask", o->mask,
                    "The mask a fabrication file was exported from: spacing rule, pinhole/mark "
                    "split and the XOR comparison");
    cmd->add_option("--max-xor-um2", o->max_xor_um2,
                    "Largest XOR area (um^2) between the file's pinholes and the design's")
        ->capture_default_str();
    cmd->add_option("--shape", o->shape, "Design pinhole shape: square | circle | polygon")
        ->capture_default_str();
    cmd->add_option("--sides", o->sides, "Design polygon sides (--shape polygon)")
        ->capture_default_str();
    cmd->add_option("--hole-side", o->hole_side,
                    "Design pinhole side / diameter (length; default: the cell pitch)");
    cmd->add_option("--frame", o->frame, "Design opaque frame width (length; default 0)");
    cmd->add_option("--chord-tol", o->chord_tol,
                    "Design circle chord tolerance (length; default 10nm, as export)");
    cmd->add_option("--list", o->list, "Violations listed per rule (all are counted)")
        ->capture_default_str();
    cmd->add_flag("--json", o->json,
                  "Print {clean, input, kind, vendor, tone, polygons, annotations, rules, "
                  "measured, counts, truncated, violations: [{rule, message, x_um, y_um, "
                  "polygon_a, polygon_b, value, limit, unit}], comparison} on stdout");
    cmd->callback([o] { run(*o); });
}

const Registration kCheck(80, "check", setup);

}  // namespace
}  // namespace pinmask::cli
