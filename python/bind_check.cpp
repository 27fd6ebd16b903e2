// The design-rule check: check() follows `pinmask check` (cli/cmd_check.cpp) and returns what
// its --json prints. Both run the library's transaction export/pipeline/check_run: a mask,
// export/pipeline/drc on its layout; a fabrication file, export/pipeline/file_check (the DRC and
// the export/pipeline/read_back comparison with the design) and the film's identity. The layout
// settings come from the export sidecar beside the file when there is one (as the CLI;
// io/sidecar_layout), else from the arguments.
#include <cmath>
#include <filesystem>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/layout/xor_area.hpp"
#include "export/pipeline/check_run.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/file_check.hpp"
#include "export/pipeline/film_identity.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"
#include "io/sidecar_identity.hpp"
#include "io/sidecar_layout.hpp"
#include "python/common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

namespace fs = std::filesystem;

std::int64_t length_nm(const py::object& v, const std::string& field, std::int64_t min_nm) {
    const double nm = std::round(length_value(v, field, false) * 1e9);
    if (!(nm >= double(min_nm)) || nm > 1e12) {
        throw invalid_field(field, py::str(v).cast<std::string>(),
                            "must be at least " + std::to_string(min_nm) + " nm");
    }
    return static_cast<std::int64_t>(nm);
}

struct CheckArgs {
    py::object min_gap, min_feature, min_spacing;
    std::optional<std::size_t> max_vertices;
    std::size_t list = 20;
    std::optional<std::string> shape;
    std::optional<int> sides;
    py::object hole_side, frame, chord_tol;
    std::optional<std::string> tone, units;
    bool mirror = false;
};

DrcRules resolve_rules(const CheckArgs& o, DrcRules rules) {
    if (!o.min_gap.is_none()) rules.min_gap_nm = length_nm(o.min_gap, field_ref("min_gap"), 1);
    if (!o.min_feature.is_none())
        rules.min_feature_nm = length_nm(o.min_feature, field_ref("min_feature"), 0);
    if (!o.min_spacing.is_none())
        rules.min_center_spacing_nm = double(length_nm(o.min_spacing, field_ref("min_spacing"), 0));
    if (o.max_vertices) rules.max_vertices = *o.max_vertices;
    if (o.list < 1) throw invalid_field(field_ref("list"), std::to_string(o.list), "must be >= 1");
    rules.max_reported_per_rule = o.list;
    return rules;
}

// The given layout settings (io/sidecar_layout: the same rules as `pinmask check`); a length is
// a float in metres or a string with a unit, read by the same parser.
io::CheckLayoutSettings layout_settings(const CheckArgs& o) {
    const auto text = [](const py::object& v) -> std::optional<std::string> {
        if (v.is_none()) return std::nullopt;
        return py::str(v).cast<std::string>();
    };
    io::CheckLayoutText given;
    given.shape = o.shape;
    given.sides = o.sides;
    given.hole_side = text(o.hole_side);
    given.frame = text(o.frame);
    given.chord_tol = text(o.chord_tol);
    given.tone = o.tone;
    given.units = o.units;
    given.mirror = o.mirror;
    return io::check_layout_settings(given);
}

py::object um_or_none(double nm) {
    return std::isfinite(nm) ? py::object(py::float_(nm * 1e-3)) : py::object(py::none());
}

py::object index_or_none(std::size_t i) {
    return i == kNoPolygon ? py::object(py::none()) : py::object(py::int_(i));
}

}  // namespace

void bind_check(py::module_& m) {
    m.def(
        "check",
        [](const py::handle& input, const py::handle& mask,
           const std::optional<std::string>& vendor_arg, const py::object& min_gap_arg,
           const py::object& min_space, const py::object& min_feature,
           const py::object& min_spacing, std::optional<std::size_t> max_vertices, std::size_t list,
           double max_xor_um2, const std::optional<std::string>& shape, std::optional<int> sides,
           const py::object& hole_side, const py::object& frame, const py::object& chord_tol,
           const std::optional<std::string>& tone, const std::optional<std::string>& units,
           bool mirror, bool no_sidecar) {
            if (!min_gap_arg.is_none() && !min_space.is_none())
                throw invalid_field(
                    field_ref("min_space"), py::str(min_space).cast<std::string>(),
                    "is the same rule as " + field_ref("min_gap") + ": give one of them");
            const py::object min_gap = min_space.is_none() ? min_gap_arg : min_space;
            CheckArgs o{min_gap,   min_feature, min_spacing, max_vertices, list,  shape, sides,
                        hole_side, frame,       chord_tol,   tone,         units, mirror};
            const io::CheckLayoutSettings given = layout_settings(o);
            // The keywords' overrides, read with the GIL (the library calls them without it).
            const RuleOverrides overrides = [&o](DrcRules rules) {
                py::gil_scoped_acquire gil;
                return resolve_rules(o, rules);
            };
            if (!std::isfinite(max_xor_um2) || max_xor_um2 < 0)
                throw invalid_field(field_ref("max_xor_um2"), std::to_string(max_xor_um2),
                                    "must be finite and >= 0");
            const bool input_is_mask = py::isinstance<Mask>(input);
            const std::string input_text =
                input_is_mask ? std::string("python mask") : py::str(input).cast<std::string>();
            if (!input_is_mask && !fs::is_regular_file(input_text))
                throw invalid_field("input", input_text,
                                    "must be an existing mask or fabrication file");
            // The vendor: as given, else the rules the export sidecar records, else film.
            std::optional<io::ExportSidecar> side;
            const fs::path side_path =
                input_is_mask ? fs::path() : io::sidecar_path_for(input_text);
            if (!input_is_mask && !io::is_mask_file(input_text) && !no_sidecar &&
                fs::is_regular_file(side_path))
                side = io::read_export_sidecar(side_path);
            std::string rules_from = vendor_arg ? "given"
                                     : side     ? "the export sidecar"
                                                : "default (film)";
            const VendorRules vendor = vendor_arg ? vendor_rules_for(*vendor_arg)
                                       : side     ? io::sidecar_rules(*side)
                                                  : vendor_rules("film");
            const std::string vendor_name = vendor.name;
            Layout l;
            DrcRules rules;
            std::string kind;
            std::optional<py::dict> comparison;
            bool comparison_ok = true;
            std::string settings;
            DrcReport r;
            FilmIdentity identity;  // a fabrication file's layer / polarity (none for a mask)
            if (input_is_mask || io::is_mask_file(input_text)) {
                if (!mask.is_none())
                    throw invalid_field(field_ref("mask"), py::str(mask).cast<std::string>(),
                                        "only used with a fabrication file");
                kind = "mask";
                const Mask mk = input_is_mask ? input.cast<Mask>()
                                              : io::read_mask_file(
                                                    input_text, {.allow_spacing_violations = true});
                const LayoutOptions lo = io::check_layout(given, nullptr);
                CheckRun run;
                {
                    py::gil_scoped_release release;  // the overrides take it back
                    run = check_mask(mk, lo, vendor, overrides, input_text);
                }
                l = std::move(run.check.layout);
                rules = run.rules;
                r = std::move(run.check.drc);
            } else {
                const FileGeometry file = read_fabrication_file(input_text);
                kind = fs::path(input_text).extension().string().substr(1);
                std::optional<Mask> design_mask;
                std::string mask_text;
                if (!mask.is_none()) {
                    design_mask = mask_arg(mask, true);
                    mask_text = py::str(mask).cast<std::string>();
                }
                if (side) {
                    settings = "from " + side_path.string();
                    if (!design_mask) {
                        mask_text = io::sidecar_mask(*side, side_path);
                        if (!mask_text.empty())
                            design_mask =
                                io::read_mask_file(mask_text, {.allow_spacing_violations = true});
                    }
                    io::check_sidecar_unit(*side, file);
                } else {
                    settings = "from the flags (no sidecar " + side_path.filename().string() + ")";
                }
                FabricationCheckRequest q;
                q.input = input_text;
                q.vendor = vendor;
                q.overrides = overrides;
                q.max_xor_nm2 = max_xor_um2 * 1e6;
                if (design_mask) {
                    q.layout = io::check_layout(given, side ? &*side : nullptr);
                    if (!side) io::apply_file_declarations(q.layout, file);
                    q.mask = &*design_mask;
                    q.whole_layout = side.has_value();
                } else if (side) {
                    const auto& a = side->active_area_nm;
                    const std::int64_t fr = std::llround(side->frame_m * 1e9);
                    q.outline = BoxNm{a[0] - fr, a[1] - fr, a[2] + fr, a[3] + fr};
                }
                q.film = io::film_identity_expected(input_text, side ? &*side : nullptr, side_path,
                                                    no_sidecar, vendor_arg, tone);
                CheckRun run;
                {
                    py::gil_scoped_release release;    // the overrides take it back
                    run = check_fabrication(file, q);  // export/pipeline/check_run
                }
                const FileCheck& fc = run.check;
                rules = run.rules;
                l = fc.layout;
                r = fc.drc;
                identity = fc.identity;
                if (fc.comparison) {
                    const ReadBack& k = *fc.comparison;
                    comparison_ok =
                        k.xor_area_nm2 <= q.max_xor_nm2 && (k.file_hash.empty() || k.hash_ok());
                    py::dict cd;
                    cd["mask"] = mask_text;
                    cd["xor_area_um2"] = k.xor_area_nm2 * 1e-6;
                    cd["max_xor_area_um2"] = max_xor_um2;
                    cd["file_hash"] = k.file_hash;
                    cd["mask_hash"] = k.design_hash;
                    cd["rings_only_in_file"] = k.only_file;
                    cd["rings_only_in_design"] = k.only_design;
                    cd["ok"] = comparison_ok;
                    comparison = cd;
                }
            }
            const bool clean = r.clean() && comparison_ok && identity.ok();
            py::list v;
            for (const DrcViolation& x : r.violations) {
                py::dict d;
                d["rule"] = drc_rule_name(x.rule);
                d["message"] = x.message;
                d["x_um"] = double(x.where.x) * 1e-3;
                d["y_um"] = double(x.where.y) * 1e-3;
                d["polygon_a"] = index_or_none(x.polygon_a);
                d["polygon_b"] = index_or_none(x.polygon_b);
                d["value"] = x.value;
                d["limit"] = x.limit;
                d["unit"] = drc_rule_unit(x.rule);
                v.append(d);
            }
            py::dict j;
            j["clean"] = clean;
            j["design_rules_checked"] = vendor_name != "none";  // as check --json
            j["input"] = input_text;
            j["kind"] = kind;
            j["vendor"] = vendor_name;
            j["rules_from"] = rules_from;
            j["settings"] = settings;
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
            if (!identity.items.empty()) {  // as check --json
                py::list items;
                for (const FilmIdentityItem& i : identity.items) {
                    py::dict d;
                    d["what"] = i.what;
                    d["found"] = i.found;
                    d["expected"] = i.expected.empty() ? py::object(py::none())
                                                       : py::object(py::str(i.expected));
                    d["source"] = i.source;
                    d["ok"] = i.ok;
                    d["message"] = i.message;
                    items.append(d);
                }
                j["film_identity"] =
                    py::dict(py::arg("ok") = identity.ok(), py::arg("items") = items);
            }
            return as_result(j);
        },
        py::arg("input"), py::arg("mask") = py::none(), py::arg("vendor") = py::none(),
        py::arg("min_gap") = py::none(), py::arg("min_space") = py::none(),
        py::arg("min_feature") = py::none(), py::arg("min_spacing") = py::none(),
        py::arg("max_vertices") = py::none(), py::arg("list") = 20, py::arg("max_xor_um2") = 0.0,
        py::arg("shape") = py::none(), py::arg("sides") = py::none(),
        py::arg("hole_side") = py::none(), py::arg("frame") = py::none(),
        py::arg("chord_tol") = py::none(), py::arg("tone") = py::none(),
        py::arg("units") = py::none(), py::arg("mirror") = false, py::arg("no_sidecar") = false,
        R"(The design-rule check of `pinmask check` (returns what its --json prints; `clean` is
its exit status): input a Mask, a *.mask.json or a fabrication file (.gds .dxf .gbr .svg); with
mask (the design a file was exported from) the file's pinholes are compared by exact XOR area
(max_xor_um2, um^2) and geometry hash. A fabrication file's export sidecar NAME.export.json
beside it (written by export) gives the layout settings (tone, mirroring, shape, frame, marks,
label) and the mask when mask is None; the given shape/sides/hole_side/frame/chord_tol/tone/
units/mirror must then agree with it (ValueError naming the flag); no_sidecar ignores it.
Without a sidecar those arguments describe the design as given to export (tone, mirroring and
grid as the file declares them). vendor: an export preset (chrome-photomask, film-plotter, ...)
or rules film | chrome | none; None: the rules the export sidecar records (vendor and any
min_feature / min_space given to export), else film. min_space (alias min_gap), min_feature,
min_spacing override them (lengths). The spacing rule is min_spacing_cells x the pinhole side on
the fabrication grid. What identifies the film (GDSII/OASIS layer and datatype, DXF layer name,
Gerber polarity) is compared with the sidecar's entry for the file, else with a vendor preset
(export's default layers, the preset's tone) and tone: film_identity {ok, items: [{what, found,
expected (None: not known), source, ok, message}]}; a mismatch makes clean False. Distances in
the result are in um.)");
}

}  // namespace pinmask::python
