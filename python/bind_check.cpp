// The design-rule check: check() is `pinmask check`, one call of the transaction io/check_files
// (the export sidecar, the vendor's rules, the design mask, export/pipeline/check_run's check of
// a mask, a fabrication file or a picture), its report rendered by io/check_json as the
// command's --json. Here the keywords are parsed into the request.
#include <cmath>
#include <filesystem>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"
#include "export/pipeline/drc.hpp"
#include "io/check_files.hpp"
#include "io/check_json.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
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
    rules.max_reported_per_rule = o.list;  // >= 1, checked before the call
    return rules;
}

// The given layout settings as text (io/check_files parses them as the command's flags: a
// length is a float in metres or a string with a unit, read by the same parser).
io::CheckLayoutText layout_text(const CheckArgs& o) {
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
    return given;
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
            if (!std::isfinite(max_xor_um2) || max_xor_um2 < 0)
                throw invalid_field(field_ref("max_xor_um2"), std::to_string(max_xor_um2),
                                    "must be finite and >= 0");
            if (list < 1)
                throw invalid_field(field_ref("list"), std::to_string(list), "must be >= 1");
            io::CheckRequest q;
            q.layout = layout_text(o);
            io::check_layout_settings(q.layout);  // the lengths' checks before any file is read
            std::optional<Mask> input_mask, design_mask;
            if (py::isinstance<Mask>(input)) {
                input_mask = input.cast<Mask>();
                q.input = "python mask";
                q.input_mask = &*input_mask;
            } else {
                q.input = py::str(input).cast<std::string>();
                if (!fs::is_regular_file(q.input))
                    throw invalid_field("input", q.input,
                                        "must be an existing mask or fabrication file");
            }
            if (!mask.is_none()) {
                q.mask = py::str(mask).cast<std::string>();
                if (py::isinstance<Mask>(mask)) {
                    design_mask = mask.cast<Mask>();
                    q.mask_value = &*design_mask;
                }
            }
            q.vendor = vendor_arg;
            // The keywords' overrides, read with the GIL (the library calls them without it).
            q.overrides = [&o](DrcRules rules) {
                py::gil_scoped_acquire gil;
                return resolve_rules(o, rules);
            };
            q.spacing_given = !min_spacing.is_none();
            q.max_xor_um2 = max_xor_um2;
            q.no_sidecar = no_sidecar;
            q.list = list;
            io::CheckReport r;
            {
                py::gil_scoped_release release;  // the overrides take it back
                r = io::run_check(q);
            }
            return as_result(py::dict(json_value(io::check_json(r))));
        },
        py::arg("input"), py::arg("mask") = py::none(), py::arg("vendor") = py::none(),
        py::arg("min_gap") = py::none(), py::arg("min_space") = py::none(),
        py::arg("min_feature") = py::none(), py::arg("min_spacing") = py::none(),
        py::arg("max_vertices") = py::none(), py::arg("list") = 20, py::arg("max_xor_um2") = 0.0,
        py::arg("shape") = py::none(), py::arg("sides") = py::none(),
        py::arg("hole_side") = py::none(), py::arg("frame") = py::none(),
        py::arg("chord_tol") = py::none(), py::arg("tone") = py::none(),
        py::arg("units") = py::none(), py::arg("mirror") = false, py::arg("no_sidecar") = false,
        R"(The design-rule check of `pinmask check`; returns what its --json prints (io/check_json;
`clean` is its exit status): input a Mask, a *.mask.json, a fabrication file (.gds .oas .dxf
.gbr .svg) or a picture export wrote (.pdf .png .tif: compared with its design, the mask given
or the one its sidecar names, under 'picture' {method, result, ok}); with
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
