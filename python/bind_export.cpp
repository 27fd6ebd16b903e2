// Fabrication export and the design-rule check (export/geometry, write_any, read_any, drc,
// xor_area). export_mask() follows `pinmask export` (cli/cmd_export.cpp) for the fabrication
// files: same layout options, same bytes, the same read-back verification; the export sidecar
// and the PSF files are the CLI's (write_psf() writes the PSF). check() follows `pinmask check`
// (cli/cmd_check.cpp) and returns what its --json prints. Both re-point at export/read_back when
// that library call exists (issue 11).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "export/drc.hpp"
#include "export/geometry.hpp"
#include "export/read_any.hpp"
#include "export/rings.hpp"
#include "export/vendor_rules.hpp"
#include "export/write_any.hpp"
#include "export/xor_area.hpp"
#include "io/mask_json.hpp"
#include "python/common.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

namespace fs = std::filesystem;

py::array_t<std::int64_t> ring_array(const Ring& r) {
    py::array_t<std::int64_t> a({static_cast<py::ssize_t>(r.size()), py::ssize_t{2}});
    auto v = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < r.size(); ++i) {
        v(static_cast<py::ssize_t>(i), 0) = r[i].x;
        v(static_cast<py::ssize_t>(i), 1) = r[i].y;
    }
    return a;
}

py::list rings_list(const std::vector<Ring>& rings) {
    py::list l;
    for (const Ring& r : rings) l.append(ring_array(r));
    return l;
}

py::tuple box_tuple(const BoxNm& b) { return py::make_tuple(b.x0, b.y0, b.x1, b.y1); }

struct LayoutArgs {
    std::string tone = "clear", shape = "square";
    int sides = 8;
    bool mirror = false, marks = false;
    std::optional<std::string> label;  // label id; None: no label
    py::object frame, chord_tol, grid, hole_side;
    std::size_t max_vertices = kGdsFriendlyMaxVertices;
};

double length_arg(const py::object& v, const char* flag) { return length_value(v, flag, false); }

LayoutOptions layout_options(const LayoutArgs& a, const Mask& mask) {
    LayoutOptions lo;
    lo.tone = parse_tone(a.tone, "--tone");
    lo.shape = parse_hole_shape(a.shape, "--shape");
    lo.polygon_sides = a.sides;
    lo.mirror = a.mirror;
    lo.marks = a.marks;
    lo.frame_m = length_arg(a.frame, "--frame");
    if (!(py::isinstance<py::str>(a.chord_tol) && a.chord_tol.cast<std::string>() == "auto")) {
        lo.chord_tolerance_m = length_arg(a.chord_tol, "--chord-tol");
        if (!(lo.chord_tolerance_m > 0))
            throw invalid_field("--chord-tol", py::str(a.chord_tol).cast<std::string>(),
                                "must be > 0 (or auto)");
    }
    lo.grid_m = length_arg(a.grid, "--grid");
    if (!a.hole_side.is_none()) lo.hole_side_m = length_arg(a.hole_side, "--hole-side");
    lo.max_vertices = a.max_vertices;
    if (a.label) lo.label_lines = default_label_lines(mask, *a.label);
    return lo;
}

bool ring_less(const Ring& a, const Ring& b) {
    return std::lexicographical_compare(
        a.begin(), a.end(), b.begin(), b.end(),
        [](const PointNm& p, const PointNm& q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
}

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) throw RuntimeFailure("cannot read back " + p.string());
    return s.str();
}

// `pinmask export`'s verify(): the file read back from disk against the design.
std::string verify(const fs::path& tmp, FabFormat f, const std::vector<Ring>& design,
                   const Layout& l) {
    const FileGeometry g = read_fabrication_bytes(file_bytes(tmp), f);
    const std::vector<Ring> got = canonical_rings(g.rings);
    const auto hash = g.info.find("hash");
    if (hash == g.info.end() || hash->second != l.mask_hash)
        throw RuntimeFailure(fab_format_name(f) + " file read back lacks the mask hash");
    if (got == design)
        return "read back: " + std::to_string(got.size()) + " polygons identical to the design";
    std::vector<Ring> only_file, only_design;
    std::set_difference(got.begin(), got.end(), design.begin(), design.end(),
                        std::back_inserter(only_file), ring_less);
    std::set_difference(design.begin(), design.end(), got.begin(), got.end(),
                        std::back_inserter(only_design), ring_less);
    const double xor_nm2 = xor_area_nm2(only_file, only_design);
    if (xor_nm2 != 0)
        throw RuntimeFailure(fab_format_name(f) + " file read back differs from the design: " +
                             std::to_string(only_file.size()) + " rings only in the file, " +
                             std::to_string(only_design.size()) + " only in the design, XOR area " +
                             std::to_string(xor_nm2 * 1e-6) + " um^2");
    return "read back: same area as the design (XOR 0), " + std::to_string(got.size()) +
           " polygons";
}

std::vector<FabFormat> parse_formats(const std::vector<std::string>& list) {
    std::vector<FabFormat> out;
    for (const std::string& item : list) {
        const FabFormat f = parse_fab_format(item, "--format");
        if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    }
    if (out.empty()) throw invalid_field("--format", "[]", "names no format");
    return out;
}

// ---- check (cli/cmd_check.cpp) ----

std::int64_t length_nm(const py::object& v, const char* flag, std::int64_t min_nm) {
    const double nm = std::round(length_value(v, flag, false) * 1e9);
    if (!(nm >= double(min_nm)) || nm > 1e12) {
        throw invalid_field(flag, py::str(v).cast<std::string>(),
                            "must be at least " + std::to_string(min_nm) + " nm");
    }
    return static_cast<std::int64_t>(nm);
}

struct CheckArgs {
    py::object min_gap, min_feature, min_spacing;
    std::optional<std::size_t> max_vertices;
    std::size_t list = 20;
    std::string shape = "square";
    int sides = 8;
    py::object hole_side, frame, chord_tol;
};

DrcRules resolve_rules(const CheckArgs& o, DrcRules rules) {
    if (!o.min_gap.is_none()) rules.min_gap_nm = length_nm(o.min_gap, "--min-gap", 1);
    if (!o.min_feature.is_none())
        rules.min_feature_nm = length_nm(o.min_feature, "--min-feature", 0);
    if (!o.min_spacing.is_none())
        rules.min_center_spacing_nm = double(length_nm(o.min_spacing, "--min-spacing", 0));
    if (o.max_vertices) rules.max_vertices = *o.max_vertices;
    if (o.list < 1) throw invalid_field("--list", std::to_string(o.list), "must be >= 1");
    rules.max_reported_per_rule = o.list;
    return rules;
}

LayoutOptions design_options(const CheckArgs& o, const FileGeometry* file) {
    LayoutOptions lo;
    lo.shape = parse_hole_shape(o.shape, "--shape");
    lo.polygon_sides = o.sides;
    if (!o.hole_side.is_none()) lo.hole_side_m = length_value(o.hole_side, "--hole-side", false);
    if (!o.frame.is_none()) lo.frame_m = length_value(o.frame, "--frame", false);
    if (!o.chord_tol.is_none())
        lo.chord_tolerance_m = length_value(o.chord_tol, "--chord-tol", false);
    if (file) {
        const auto& info = file->info;
        if (auto it = info.find("tone"); it != info.end()) lo.tone = parse_tone(it->second, "tone");
        if (auto it = info.find("mirrored"); it != info.end()) lo.mirror = it->second == "yes";
        if (auto it = info.find("grid_nm"); it != info.end())
            lo.grid_m = parse_number(it->second, "grid_nm") * 1e-9;
    }
    return lo;
}

bool box_inside(const BoxNm& inner, const BoxNm& outer) {
    return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x1 <= outer.x1 &&
           inner.y1 <= outer.y1;
}

bool is_mask_file(const fs::path& path) {
    if (path.extension() == ".json") return true;
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    }
    return in && c == '{';
}

py::object um_or_none(double nm) {
    return std::isfinite(nm) ? py::object(py::float_(nm * 1e-3)) : py::object(py::none());
}

py::object index_or_none(std::size_t i) {
    return i == kNoPolygon ? py::object(py::none()) : py::object(py::int_(i));
}

}  // namespace

void bind_export(py::module_& m) {
    py::class_<Layout>(m, "Layout",
                       "Mask geometry for fabrication in integer nanometres (origin at the mask "
                       "centre, y up): polygons (each a (k, 2) int64 array of x, y in nm, "
                       "counter-clockwise), annotations (marks, label), boxes (x0, y0, x1, y1).")
        .def_property_readonly("polygons", [](const Layout& l) { return rings_list(l.polygons); })
        .def_property_readonly("annotations",
                               [](const Layout& l) { return rings_list(l.annotations); })
        .def_property_readonly("active_area",
                               [](const Layout& l) { return box_tuple(l.active_area); })
        .def_property_readonly("extent", [](const Layout& l) { return box_tuple(l.extent); })
        .def_property_readonly("tone", [](const Layout& l) { return tone_name(l.tone); })
        .def_readonly("mirrored", &Layout::mirrored)
        .def_readonly("grid_nm", &Layout::grid_nm)
        .def_readonly("mask_hash", &Layout::mask_hash);

    auto layout_fn =
        [](const py::handle& mask_obj, const std::string& tone, const std::string& shape, int sides,
           bool mirror, bool marks, const std::optional<std::string>& label,
           const py::object& frame, const py::object& chord_tol, const py::object& grid,
           const py::object& hole_side, std::size_t max_vertices, bool allow_spacing_violations) {
            const Mask mk = mask_arg(mask_obj, allow_spacing_violations);
            LayoutArgs a{tone,  shape,     sides, mirror,    marks,       label,
                         frame, chord_tol, grid,  hole_side, max_vertices};
            const LayoutOptions lo = layout_options(a, mk);
            py::gil_scoped_release release;
            return make_layout(mk, lo);
        };
    m.def("layout", layout_fn, py::arg("mask"), py::arg("tone") = "clear",
          py::arg("shape") = "square", py::arg("sides") = 8, py::arg("mirror") = false,
          py::arg("marks") = false, py::arg("label") = py::none(), py::arg("frame") = "0",
          py::arg("chord_tol") = "auto", py::arg("grid") = "1nm", py::arg("hole_side") = py::none(),
          py::arg("max_vertices") = kGdsFriendlyMaxVertices,
          py::arg("allow_spacing_violations") = false,
          "The fabrication layout `pinmask export` builds: tone clear|dark, shape "
          "square|circle|polygon (sides), mirror (emulsion side), alignment marks, label (its id "
          "string, or None for none), frame width, chord_tol ('auto' or a length), grid "
          "(manufacturing grid), hole_side (default the cell pitch); lengths in metres or with "
          "a unit ('1mm').");

    m.def(
        "fabrication_bytes",
        [](const Layout& layout, const std::string& format, int layer, int datatype,
           const std::string& dxf_layer, double dpi, const py::object& margin) {
            WriteOptions w;
            w.gds = {.layer = layer, .datatype = datatype};
            w.dxf = {.layer = dxf_layer};
            w.pdf.margin_m = length_value(margin, "--margin", false);
            w.png_dpi = dpi;
            const FabFormat f = parse_fab_format(format, "--format");
            std::string bytes;
            {
                py::gil_scoped_release release;
                bytes = write_fabrication_bytes(layout, f, w);
            }
            return py::bytes(bytes);
        },
        py::arg("layout"), py::arg("format"), py::arg("layer") = 1, py::arg("datatype") = 0,
        py::arg("dxf_layer") = "PINMASK", py::arg("dpi") = 2400.0, py::arg("margin") = "10mm",
        "The bytes of one fabrication file: svg | pdf | gds | dxf | gerber | png (GDS layer and "
        "datatype, DXF layer name, PNG dots per inch, PDF margin).");

    m.def(
        "export_mask",
        [layout_fn](
            const py::handle& mask_obj, const std::string& out_dir,
            const std::vector<std::string>& formats, const std::optional<std::string>& stem_opt,
            const std::string& tone, const std::string& shape, int sides, bool mirror, bool marks,
            bool label, const std::string& label_id, const py::object& frame,
            const py::object& chord_tol, const py::object& grid, const py::object& hole_side,
            std::size_t max_vertices, int layer, int datatype, const std::string& dxf_layer,
            double dpi, const py::object& margin, const std::string& vendor, bool require_drc_clean,
            bool allow_spacing_violations) {
            const std::vector<FabFormat> fmts = parse_formats(formats);
            if (out_dir.empty()) throw invalid_field("-o", "''", "an output directory is required");
            if (fs::exists(out_dir) && !fs::is_directory(out_dir))
                throw invalid_field("-o", out_dir, "exists and is not a directory");
            const Mask mk = mask_arg(mask_obj, allow_spacing_violations);
            std::string stem = stem_opt.value_or("");
            if (stem.empty()) {
                if (py::isinstance<Mask>(mask_obj)) {
                    stem = "mask";
                } else {
                    stem = fs::path(py::str(mask_obj).cast<std::string>()).filename().string();
                    for (const char* suffix : {".mask.json", ".json"}) {
                        const std::string s(suffix);
                        if (stem.size() > s.size() && stem.ends_with(s)) {
                            stem = stem.substr(0, stem.size() - s.size());
                            break;
                        }
                    }
                }
            }
            if (stem.empty() || stem.find('/') != std::string::npos)
                throw invalid_field("--stem", stem, "must be a plain file name");
            const Layout layout =
                layout_fn(py::cast(mk), tone, shape, sides, mirror, marks,
                          label ? std::optional<std::string>(label_id.empty() ? stem : label_id)
                                : std::nullopt,
                          frame, chord_tol, grid, hole_side, max_vertices, true);
            WriteOptions w;
            w.gds = {.layer = layer, .datatype = datatype};
            w.dxf = {.layer = dxf_layer};
            w.pdf.margin_m = length_value(margin, "--margin", false);
            w.png_dpi = dpi;
            const VendorRules rules = vendor_rules(vendor);
            py::list files;
            DrcReport drc;
            {
                py::gil_scoped_release release;
                const std::vector<Ring> design = canonical_rings(all_rings(layout));
                drc = run_drc(layout, rules_for_mask(mk, rules));
                if (require_drc_clean && !drc.clean()) {
                    std::string what;
                    for (const auto& [rule, n] : drc.counts)
                        what += " " + rule + "=" + std::to_string(n);
                    throw RuntimeFailure("design-rule check (" + vendor + ") found violations:" +
                                         what + "; run `pinmask check` for details");
                }
                std::vector<std::pair<FabFormat, std::string>> contents;
                for (FabFormat f : fmts)
                    contents.push_back({f, write_fabrication_bytes(layout, f, w)});
                fs::create_directories(out_dir);
                StagedFiles staged;
                std::vector<std::tuple<std::string, std::string, std::size_t, std::string>> info;
                for (const auto& entry : contents) {
                    const FabFormat f = entry.first;
                    const std::string& bytes = entry.second;
                    const fs::path path = fs::path(out_dir) / (stem + fab_extension(f));
                    std::string check = "not readable (written only)";
                    staged.stage(path, [&](const fs::path& tmp) {
                        {
                            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
                            out.write(bytes.data(), std::streamsize(bytes.size()));
                            if (!out) throw RuntimeFailure("cannot write " + tmp.string());
                        }
                        if (is_readable(f)) check = verify(tmp, f, design, layout);
                    });
                    info.emplace_back(path.string(), fab_format_name(f), bytes.size(), check);
                }
                staged.commit();
                py::gil_scoped_acquire gil;
                for (const auto& [path, format, size, check] : info) {
                    py::dict d;
                    d["path"] = path;
                    d["format"] = format;
                    d["bytes"] = size;
                    d["verification"] = check;
                    files.append(d);
                }
            }
            py::dict out;
            out["files"] = files;
            out["drc"] = py::dict(py::arg("vendor") = vendor, py::arg("clean") = drc.clean(),
                                  py::arg("counts") = drc.counts);
            out["mask_hash"] = layout.mask_hash;
            return out;
        },
        py::arg("mask"), py::arg("out_dir"),
        py::arg("formats") = std::vector<std::string>{"svg", "pdf", "gds", "dxf", "gerber", "png"},
        py::arg("stem") = py::none(), py::arg("tone") = "clear", py::arg("shape") = "square",
        py::arg("sides") = 8, py::arg("mirror") = false, py::arg("marks") = false,
        py::arg("label") = false, py::arg("label_id") = "", py::arg("frame") = "0",
        py::arg("chord_tol") = "auto", py::arg("grid") = "1nm", py::arg("hole_side") = py::none(),
        py::arg("max_vertices") = kGdsFriendlyMaxVertices, py::arg("layer") = 1,
        py::arg("datatype") = 0, py::arg("dxf_layer") = "PINMASK", py::arg("dpi") = 2400.0,
        py::arg("margin") = "10mm", py::arg("vendor") = "none",
        py::arg("require_drc_clean") = false, py::arg("allow_spacing_violations") = false,
        R"(Writes the fabrication files of `pinmask export MASK -o out_dir` (same options, same
bytes): out_dir/<stem>.svg .pdf .gds .dxf .gbr .png, all or nothing; each readable format is read
back from disk and compared with the design (identical polygons or XOR area 0, and the mask
hash), else RuntimeError and no file. The design-rule check (vendor film | chrome | none) is
reported (require_drc_clean: RuntimeError on violations). stem: default the mask file's name
('mask' for a Mask object). The export sidecar JSON and the PSF files are the CLI's; write_psf()
writes the PSF. Returns {files: [{path, format, bytes, verification}], drc: {vendor, clean,
counts}, mask_hash}.)");

    m.def(
        "check",
        [](const py::handle& input, const py::handle& mask, const std::string& vendor_name,
           const py::object& min_gap, const py::object& min_feature, const py::object& min_spacing,
           std::optional<std::size_t> max_vertices, std::size_t list, double max_xor_um2,
           const std::string& shape, int sides, const py::object& hole_side,
           const py::object& frame, const py::object& chord_tol) {
            CheckArgs o{min_gap, min_feature, min_spacing, max_vertices, list,
                        shape,   sides,       hole_side,   frame,        chord_tol};
            if (!std::isfinite(max_xor_um2) || max_xor_um2 < 0)
                throw invalid_field("--max-xor-um2", std::to_string(max_xor_um2),
                                    "must be finite and >= 0");
            const VendorRules vendor = vendor_rules(vendor_name);
            const bool input_is_mask = py::isinstance<Mask>(input);
            const std::string input_text =
                input_is_mask ? std::string("python mask") : py::str(input).cast<std::string>();
            if (!input_is_mask && !fs::is_regular_file(input_text))
                throw invalid_field("input", input_text,
                                    "must be an existing mask or fabrication file");
            Layout l;
            DrcRules rules;
            std::string kind;
            std::optional<py::dict> comparison;
            bool comparison_ok = true;
            if (input_is_mask || is_mask_file(input_text)) {
                if (!mask.is_none())
                    throw invalid_field("--mask", py::str(mask).cast<std::string>(),
                                        "only used with a fabrication file");
                kind = "mask";
                const Mask mk = input_is_mask ? input.cast<Mask>()
                                              : io::read_mask_file(
                                                    input_text, {.allow_spacing_violations = true});
                l = make_layout(mk, design_options(o, nullptr));
                rules = resolve_rules(o, rules_for_mask(mk, vendor));
            } else {
                const FileGeometry file = read_fabrication_file(input_text);
                kind = fs::path(input_text).extension().string().substr(1);
                const auto tone = file.info.find("tone");
                l.tone = tone == file.info.end() ? Tone::kClear : parse_tone(tone->second, "tone");
                l.extent = bounding_box(file.rings);
                if (mask.is_none()) {
                    l.polygons = file.rings;
                    l.active_area = l.extent;
                    DrcRules r;
                    r.min_gap_nm = vendor.min_gap_nm;
                    r.min_feature_nm = vendor.min_feature_nm;
                    r.max_vertices = vendor.max_vertices;
                    rules = resolve_rules(o, r);
                } else {
                    const Mask mk = mask_arg(mask, true);
                    const Layout design = make_layout(mk, design_options(o, &file));
                    const BoxNm outline = bounding_box(design.polygons);
                    for (const Ring& r : file.rings)
                        (box_inside(bounding_box({r}), outline) ? l.polygons : l.annotations)
                            .push_back(r);
                    l.active_area = design.active_area;
                    l.extent = box_union(l.extent, design.extent);
                    rules = resolve_rules(o, rules_for_mask(mk, vendor));
                    const double xor_um2 = xor_area_nm2(l.polygons, design.polygons) * 1e-6;
                    const std::string mask_hash = geometry_hash(mk);
                    std::string file_hash;
                    if (auto it = file.info.find("hash"); it != file.info.end())
                        file_hash = it->second;
                    comparison_ok =
                        xor_um2 <= max_xor_um2 && (file_hash.empty() || file_hash == mask_hash);
                    py::dict c;
                    c["mask"] = py::str(mask);
                    c["xor_area_um2"] = xor_um2;
                    c["max_xor_area_um2"] = max_xor_um2;
                    c["file_hash"] = file_hash;
                    c["mask_hash"] = mask_hash;
                    c["ok"] = comparison_ok;
                    comparison = c;
                }
            }
            DrcReport r;
            {
                py::gil_scoped_release release;
                r = run_drc(l, rules);
            }
            const bool clean = r.clean() && comparison_ok;
            py::list v;
            for (const DrcViolation& x : r.violations) {
                py::dict d;
                d["rule"] = x.rule;
                d["message"] = x.message;
                d["x_um"] = double(x.where.x) * 1e-3;
                d["y_um"] = double(x.where.y) * 1e-3;
                d["polygon_a"] = index_or_none(x.polygon_a);
                d["polygon_b"] = index_or_none(x.polygon_b);
                d["value"] = x.value;
                d["limit"] = x.limit;
                d["unit"] = x.rule == "vertices" || x.rule == "ring" ? "vertices" : "nm";
                v.append(d);
            }
            py::dict j;
            j["clean"] = clean;
            j["input"] = input_text;
            j["kind"] = kind;
            j["vendor"] = vendor_name;
            j["tone"] = tone_name(l.tone);
            j["polygons"] = l.polygons.size();
            j["annotations"] = l.annotations.size();
            j["rules"] =
                py::dict(py::arg("min_center_spacing_um") = rules.min_center_spacing_nm * 1e-3,
                         py::arg("min_gap_um") = double(rules.min_gap_nm) * 1e-3,
                         py::arg("min_feature_um") = double(rules.min_feature_nm) * 1e-3,
                         py::arg("max_vertices") = rules.max_vertices);
            j["measured"] = py::dict(
                py::arg("min_center_spacing_um") = um_or_none(r.measured.min_center_spacing_nm),
                py::arg("min_gap_um") = um_or_none(r.measured.min_gap_nm),
                py::arg("min_feature_um") = um_or_none(r.measured.min_feature_nm));
            j["counts"] = r.counts;
            j["truncated"] = r.truncated;
            j["violations"] = v;
            if (comparison) j["comparison"] = *comparison;
            return j;
        },
        py::arg("input"), py::arg("mask") = py::none(), py::arg("vendor") = "film",
        py::arg("min_gap") = py::none(), py::arg("min_feature") = py::none(),
        py::arg("min_spacing") = py::none(), py::arg("max_vertices") = py::none(),
        py::arg("list") = 20, py::arg("max_xor_um2") = 0.0, py::arg("shape") = "square",
        py::arg("sides") = 8, py::arg("hole_side") = py::none(), py::arg("frame") = py::none(),
        py::arg("chord_tol") = py::none(),
        R"(The design-rule check of `pinmask check` (returns what its --json prints; `clean` is
its exit status): input a Mask, a *.mask.json or a fabrication file (.gds .dxf .gbr .svg); with
mask (the design a file was exported from) the file's pinholes are compared by exact XOR area
(max_xor_um2, um^2) and geometry hash. vendor film | chrome | none; min_gap, min_feature,
min_spacing override it (lengths); shape/sides/hole_side/frame/chord_tol describe the design
as given to export. Distances in the result are in um.)");
}

}  // namespace pinmask::python
