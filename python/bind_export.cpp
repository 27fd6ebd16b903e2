// Fabrication export. export_mask() is `pinmask export`'s library pipeline for the fabrication
// files (cli/options/export_options turns the same flags into ExportOptions;
// io/export_files write_export, the transaction the command calls: each file read back from disk
// before it is committed): same bytes, the same PSF files and the export sidecar.
// layout() builds the same layout (make_layout with the pipeline's LayoutOptions).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "export/formats/read_any.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/layout/rings.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/layout/xor_area.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/export_request.hpp"
#include "io/export_files.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
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

// `pinmask export`'s layout flags (cli/options/export_options: the same checks and defaults).
// None (tone, frame, grid, max_vertices) is "not given": the vendor preset's value, else the
// default, as the command leaves a flag out.
ExportRequest layout_flags(const std::optional<std::string>& tone, const std::string& shape,
                           std::optional<int> sides, bool mirror, bool marks,
                           const std::optional<std::string>& label, const py::object& frame,
                           const py::object& chord_tol, const py::object& grid,
                           const py::object& hole_side, std::optional<std::size_t> max_vertices) {
    ExportRequest f;
    f.tone = tone;
    f.shape = shape;
    f.sides = sides;
    f.mirror = mirror;
    f.marks = marks;
    f.label = label.has_value();
    f.label_id = label.value_or("");
    if (!frame.is_none()) f.frame = py::str(frame).cast<std::string>();
    f.chord_tol = py::str(chord_tol).cast<std::string>();
    if (!grid.is_none()) f.grid = py::str(grid).cast<std::string>();
    if (!hole_side.is_none()) f.hole_side = py::str(hole_side).cast<std::string>();
    f.max_vertices = max_vertices;
    f.no_psf = true;
    return f;
}

std::vector<FabFormat> parse_formats(const std::vector<std::string>& list) {
    std::vector<FabFormat> out;
    for (const std::string& item : list) {
        const FabFormat f = parse_fab_format(item, field_ref("formats"));
        if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    }
    if (out.empty()) throw invalid_field(field_ref("formats"), "[]", "names no format");
    return out;
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

    auto layout_fn = [](const py::handle& mask_obj, const std::string& tone,
                        const std::string& shape, std::optional<int> sides, bool mirror, bool marks,
                        const std::optional<std::string>& label, const py::object& frame,
                        const py::object& chord_tol, const py::object& grid,
                        const py::object& hole_side, std::size_t max_vertices,
                        bool allow_spacing_violations) {
        const Mask mk = mask_arg(mask_obj, allow_spacing_violations);
        ExportRequest f = layout_flags(tone, shape, sides, mirror, marks, label, frame, chord_tol,
                                       grid, hole_side, max_vertices);
        f.allow_spacing_violations = allow_spacing_violations;
        const LayoutOptions lo = export_options_from(f, mk, label.value_or("mask")).layout;
        py::gil_scoped_release release;
        return make_layout(mk, lo);
    };
    m.def("layout", layout_fn, py::arg("mask"), py::arg("tone") = "clear",
          py::arg("shape") = "square", py::arg("sides") = py::none(), py::arg("mirror") = false,
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
            w.pdf.margin_m = length_value(margin, field_ref("margin"), false);
            w.png_dpi = dpi;
            const FabFormat f = parse_fab_format(format, field_ref("format"));
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
        [](const py::handle& mask_obj, const std::string& out_dir,
           const std::optional<std::vector<std::string>>& formats,
           const std::optional<std::string>& stem_opt, const std::optional<std::string>& tone,
           const std::string& shape, std::optional<int> sides, bool mirror, bool marks, bool label,
           const std::string& label_id, const py::object& frame, const py::object& chord_tol,
           const py::object& grid, const py::object& hole_side,
           std::optional<std::size_t> max_vertices, int layer, int datatype,
           const std::string& dxf_layer, std::optional<double> dpi, const py::object& margin,
           const std::string& vendor, bool require_drc_clean, bool allow_spacing_violations,
           const std::optional<std::string>& min_feature,
           const std::optional<std::string>& min_space, const std::optional<std::string>& units,
           const std::optional<std::string>& emulsion, const std::optional<std::string>& draw,
           const std::optional<std::string>& circles, const std::string& hierarchy,
           const py::object& kerf, const py::object& max_snap_error, bool psf, bool npy,
           bool write_on_violations) {
            if (formats) parse_formats(*formats);  // None: the vendor preset's, as the command
            if (npy && !psf)
                throw InvalidInput(field_ref("npy") + " writes the PSF as .npy: it needs " +
                                   field_ref("psf") + "=True");
            if (out_dir.empty())
                throw invalid_field(field_ref("out_dir"), "''", "an output directory is required");
            if (fs::exists(out_dir) && !fs::is_directory(out_dir))
                throw invalid_field(field_ref("out_dir"), out_dir, "exists and is not a directory");
            const Mask mk = mask_arg(mask_obj, allow_spacing_violations);
            // stem: as given, else the mask file's name as the command takes it ("mask" for a
            // Mask object).
            std::string stem = stem_opt.value_or("");
            if (stem.empty())
                stem = py::isinstance<Mask>(mask_obj)
                           ? "mask"
                           : io::default_export_stem(py::str(mask_obj).cast<std::string>());
            if (stem.empty() || stem.find('/') != std::string::npos)
                throw invalid_field(field_ref("stem"), stem, "must be a plain file name");
            // `pinmask export`'s flags -> the library pipeline (export/pipeline/export_pipeline).
            ExportRequest f =
                layout_flags(tone, shape, sides, mirror, marks,
                             label ? std::optional<std::string>(label_id.empty() ? stem : label_id)
                                   : std::nullopt,
                             frame, chord_tol, grid, hole_side, max_vertices);
            if (formats) {
                f.formats = "";
                for (const std::string& x : *formats)
                    *f.formats += (f.formats->empty() ? "" : ",") + x;
            }
            f.layer = layer;
            f.datatype = datatype;
            f.dxf_layer = dxf_layer;
            f.dpi = dpi;
            f.margin = py::str(margin).cast<std::string>();
            f.vendor = vendor;
            f.min_feature = min_feature;
            f.min_space = min_space;
            f.require_drc_clean = require_drc_clean;
            f.write_on_violations = write_on_violations;
            f.allow_spacing_violations = allow_spacing_violations;
            // The command's --units, --emulsion, --draw, --circles, --hierarchy, --kerf and
            // --max-snap-error, as typed (lengths: metres or a string with a unit).
            f.units = units;
            f.emulsion = emulsion;
            f.draw = draw;
            f.circles = circles;
            f.hierarchy = hierarchy;
            if (!kerf.is_none()) f.kerf = py::str(kerf).cast<std::string>();
            if (!max_snap_error.is_none())
                f.max_snap_error = py::str(max_snap_error).cast<std::string>();
            f.no_psf = !psf;
            f.psf_npy = npy;
            // The input recorded in the sidecar: the path as given, as the command records it.
            if (!py::isinstance<Mask>(mask_obj)) f.input = py::str(mask_obj).cast<std::string>();
            const ExportOptions o = export_options_from(f, mk, stem);
            // No output may replace the mask file read (as the command's plan_outputs refuses;
            // the module leaves the process-wide input protection off, so it checks here).
            if (!f.input.empty()) {
                for (const io::ExportOutput& x : io::export_outputs(f, o, out_dir, stem))
                    if (same_file(x.path, f.input))
                        throw invalid_field(field_ref("stem"), stem,
                                            "would write " + x.path.filename().string() +
                                                " over the mask file " + f.input);
            }
            io::ExportWritten w;
            {
                py::gil_scoped_release release;
                // io/export_files, as `pinmask export` writes them: check() of these files reads
                // their layout settings and rules from the sidecar, decode --psf the PSF files.
                w = io::write_export(mk, f, o, out_dir, stem, [](const std::string& n) {
                    return py_names::spell_keywords(n);
                });
            }
            // What `export --json` prints: the sidecar <stem>.export.json, as written.
            return as_result(py::dict(json_value(nlohmann::ordered_json::parse(w.sidecar_text))));
        },
        py::arg("mask"), py::arg("out_dir"), py::arg("formats") = py::none(),
        py::arg("stem") = py::none(), py::arg("tone") = py::none(), py::arg("shape") = "square",
        py::arg("sides") = py::none(), py::arg("mirror") = false, py::arg("marks") = false,
        py::arg("label") = false, py::arg("label_id") = "", py::arg("frame") = py::none(),
        py::arg("chord_tol") = "auto", py::arg("grid") = py::none(),
        py::arg("hole_side") = py::none(), py::arg("max_vertices") = py::none(),
        py::arg("layer") = 1, py::arg("datatype") = 0, py::arg("dxf_layer") = "PINMASK",
        py::arg("dpi") = py::none(), py::arg("margin") = "10mm", py::arg("vendor") = "none",
        py::arg("require_drc_clean") = false, py::arg("allow_spacing_violations") = false,
        py::arg("min_feature") = py::none(), py::arg("min_space") = py::none(),
        py::arg("units") = py::none(), py::arg("emulsion") = py::none(),
        py::arg("draw") = py::none(), py::arg("circles") = py::none(),
        py::arg("hierarchy") = "auto", py::arg("kerf") = py::none(),
        py::arg("max_snap_error") = py::none(), py::arg("psf") = true, py::arg("npy") = false,
        py::arg("write_on_violations") = false,
        R"(Writes the fabrication files of `pinmask export MASK -o out_dir` (same options, same
bytes; export/pipeline/export_pipeline): formats svg pdf gds oasis dxf gerber png tiff1 ->
out_dir/<stem>.svg .pdf .gds .oas .dxf .gbr .png .tif, all or nothing (None: the vendor
preset's formats, else svg pdf gds dxf gerber png, as the command); dpi: PNG/TIFF
resolution (None: the CLI's default per format); each readable format is read back from disk and compared with the design (identical polygons or XOR area 0, and the mask
hash), each picture (pdf, png, tiff1) with the design drawn the same way, as the command does,
else RuntimeError and no file. The design-rule check (vendor: an export preset or rules
film | chrome | none; min_feature / min_space: the shop's own limits over them, lengths) is
checked: a violation is a RuntimeError naming every failed rule and no file is written
(require_drc_clean, the default, kept for scripts; write_on_violations=True writes the files for
inspection and reports drc.clean False); the spacing rule is evaluated on the
pinhole side snapped to the grid, the pitch every cell edge is drawn at. stem: default the mask file's name
('mask' for a Mask object). Beside the files, <stem>.export.json: the export sidecar of
`pinmask export` (settings, rules, each file's hash; check() of these files reads it). units: DXF unit and GDSII/OASIS user unit um | mm | in (default um;
Gerber always mm); emulsion up | down (= mirror); draw (PDF/PNG/SVG) film | polygons; circles
(DXF/Gerber round pinholes) native | polygon; hierarchy (GDSII) flat | cells | auto; kerf: laser
kerf, holes drawn this much smaller (a length); max_snap_error (tiff1): refuse when snapping moves
an edge more (a length); each as the command's flag of the same name, defaults and vendor
presets included. psf (as the command, unless --no-psf): also <stem>.psf.tiff and its JSON
sidecar (the mask's PSF, what decode --psf reads; npy: also <stem>.psf.npy). Returns what
`pinmask export --json` prints, the sidecar <stem>.export.json as written: {format, version,
mask: {path, geometry_hash, n, tiles, pinholes, pinhole_m}, geometry (the layout settings, unit,
tone, emulsion, boxes in nm, polygon counts), drc: {vendor, clean, counts, rules}, files:
[{name (in out_dir), format, units, bytes, fnv1a64, verification, detail}], psf: {files, kernel,
pixels_per_cell, size_px} (or why none was written), notes}.)");
}

}  // namespace pinmask::python
