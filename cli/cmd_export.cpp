// `pinmask export`: mask file -> fabrication files (SVG, PDF, GDSII, DXF, Gerber, PNG preview),
// the PSF files (cli/psf_files, as `pinmask psf` writes them) and a sidecar JSON tying every
// file to the mask's geometry hash, units, tone and mirroring. Every GDS/DXF/Gerber/SVG file is
// read back from disk and compared with the design polygons (equal canonical ring sets, or zero
// XOR area between the rings that differ); any difference makes the export fail with no files.
// The design-rule check (export/drc) runs on the layout and is reported (and enforced with
// --require-drc-clean). The fabrication files and the sidecar are staged together; the PSF
// files commit as their own group just before them and are removed if the commit fails.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/output_set.hpp"
#include "core/units.hpp"
#include "design/psf.hpp"
#include "export/drc.hpp"
#include "export/dxf_writer.hpp"
#include "export/gds_writer.hpp"
#include "export/geometry.hpp"
#include "export/gerber_writer.hpp"
#include "export/pdf_writer.hpp"
#include "export/png_preview.hpp"
#include "export/read_any.hpp"
#include "export/rings.hpp"
#include "export/svg_writer.hpp"
#include "export/vendor_rules.hpp"
#include "export/write_any.hpp"
#include "export/xor_area.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ExportOptions {
    std::string input, output, stem;
    std::string formats = "svg,pdf,gds,dxf,gerber,png";
    std::string tone = "clear", shape = "square";
    int sides = 8;
    bool mirror = false, marks = false, label = false;
    std::string label_id;
    std::string frame = "0", chord_tol = "auto", grid = "1nm", margin = "10mm";
    std::optional<std::string> hole_side;
    std::size_t max_vertices = kGdsFriendlyMaxVertices;
    int layer = 1, datatype = 0;
    std::string dxf_layer = "PINMASK";
    double dpi = 2400;
    std::string vendor = "none";
    bool require_drc_clean = false, allow_spacing_violations = false, json = false;
    bool no_psf = false, psf_npy = false;
};

std::string default_stem(const fs::path& input) {
    std::string name = input.filename().string();
    for (const char* suffix : {".mask.json", ".json"})
        if (name.size() > std::string(suffix).size() && name.ends_with(suffix))
            return name.substr(0, name.size() - std::string(suffix).size());
    return input.stem().string();
}

std::vector<FabFormat> parse_formats(const std::string& list) {
    std::vector<FabFormat> out;
    std::stringstream ss(list);
    for (std::string item; std::getline(ss, item, ',');) {
        if (item.empty()) continue;
        const FabFormat f = parse_fab_format(item, "--format");
        if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    }
    if (out.empty()) throw invalid_field("--format", list, "names no format");
    return out;
}

std::string fnv1a64(std::string_view bytes) {
    std::uint64_t h = 14695981039346656037ULL;
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) throw RuntimeFailure("cannot read back " + p.string());
    return s.str();
}

LayoutOptions layout_options(const ExportOptions& o, const Mask& mask, const std::string& stem) {
    LayoutOptions lo;
    lo.tone = parse_tone(o.tone, "--tone");
    lo.shape = parse_hole_shape(o.shape, "--shape");
    lo.polygon_sides = o.sides;
    lo.mirror = o.mirror;
    lo.marks = o.marks;
    lo.frame_m = parse_length_m(o.frame, "--frame");
    if (o.chord_tol != "auto") {
        lo.chord_tolerance_m = parse_length_m(o.chord_tol, "--chord-tol");
        if (!(lo.chord_tolerance_m > 0))
            throw invalid_field("--chord-tol", o.chord_tol, "must be > 0 (or auto)");
    }
    lo.grid_m = parse_length_m(o.grid, "--grid");
    if (o.hole_side) lo.hole_side_m = parse_length_m(*o.hole_side, "--hole-side");
    lo.max_vertices = o.max_vertices;
    if (o.label) lo.label_lines = default_label_lines(mask, o.label_id.empty() ? stem : o.label_id);
    return lo;
}

WriteOptions write_options(const ExportOptions& o) {
    WriteOptions w;
    w.gds = {.layer = o.layer, .datatype = o.datatype};
    w.dxf = {.layer = o.dxf_layer};
    w.pdf.margin_m = parse_length_m(o.margin, "--margin");
    w.png_dpi = o.dpi;
    return w;
}

std::string units_of(FabFormat f) {
    switch (f) {
        case FabFormat::kSvg:
            return "viewBox um, size mm";
        case FabFormat::kGds:
            return "database unit 1 nm, user unit 1 um";
        case FabFormat::kDxf:
            return "um";
        case FabFormat::kGerber:
            return "mm (format 4.6)";
        case FabFormat::kPdf:
            return "pt (1/72 in), scale 1:1";
        case FabFormat::kPng:
            return "pixels";
    }
    return "";
}

bool ring_less(const Ring& a, const Ring& b) {
    return std::lexicographical_compare(
        a.begin(), a.end(), b.begin(), b.end(),
        [](const PointNm& p, const PointNm& q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
}

// Reads a staged file back from disk and compares it with the design: equal canonical ring
// sets, or else zero XOR area (export/xor_area, exact) between the rings that differ (the
// common rings cancel: rings of one set never overlap). Throws RuntimeFailure (the export is
// refused) otherwise, or when the file lacks the mask hash.
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

// The PSF of one period (design/psf) and its sidecar fields, as `pinmask psf` writes them.
std::pair<Plane, io::PsfSidecar> mask_psf(const Mask& mask, const std::string& mask_path) {
    const int ppc = mask.psf.pixels_per_cell;
    check_psf_memory(mask.pattern.n, ppc, 2, 0);
    const Kernel kernel = mask_kernel(mask);
    const io::PsfSidecar s = io::psf_sidecar_for(mask, kernel, mask_path);
    return {synthesize_psf(mask.pattern, kernel, ppc), s};
}

json box_json(const BoxNm& b) { return json::array({b.x0, b.y0, b.x1, b.y1}); }

void run_export(const ExportOptions& o) {
    const std::vector<FabFormat> formats = parse_formats(o.formats);
    if (o.output.empty()) throw invalid_field("-o", "''", "an output directory is required");
    const fs::path out_dir = o.output;
    if (fs::exists(out_dir) && !fs::is_directory(out_dir))
        throw invalid_field("-o", o.output, "exists and is not a directory");
    const Mask mask =
        io::read_mask_file(o.input, {.allow_spacing_violations = o.allow_spacing_violations});
    const std::string stem = o.stem.empty() ? default_stem(o.input) : o.stem;
    if (stem.empty() || stem.find('/') != std::string::npos)
        throw invalid_field("--stem", stem, "must be a plain file name");
    {
        std::vector<NamedPath> outs{{"-o (export.json)", out_dir / (stem + ".export.json"), true}};
        for (FabFormat f : formats)
            outs.push_back({"-o", out_dir / (stem + fab_extension(f)), true});
        if (!o.no_psf) {
            const fs::path psf_tiff = out_dir / (stem + ".psf.tiff");
            outs.push_back({"-o (PSF)", psf_tiff, true});
            outs.push_back({"-o (PSF sidecar)", io::psf_sidecar_path(psf_tiff), true});
            if (o.psf_npy) outs.push_back({"-o (PSF npy)", out_dir / (stem + ".psf.npy"), true});
        }
        plan_outputs({{"input", o.input}}, outs);
    }
    const LayoutOptions lo = layout_options(o, mask, stem);
    const Layout layout = make_layout(mask, lo);
    const std::vector<Ring> design = canonical_rings(all_rings(layout));
    const DrcReport drc = run_drc(layout, rules_for_mask(mask, vendor_rules(o.vendor)));
    if (o.require_drc_clean && !drc.clean()) {
        std::string what;
        for (const auto& [rule, n] : drc.counts) what += " " + rule + "=" + std::to_string(n);
        throw RuntimeFailure("design-rule check (" + o.vendor + ") found violations:" + what +
                             "; run `pinmask check` for details");
    }

    std::optional<std::pair<Plane, io::PsfSidecar>> psf;
    if (!o.no_psf) psf = mask_psf(mask, o.input);

    std::vector<std::pair<FabFormat, std::string>> contents;
    const WriteOptions wo = write_options(o);
    for (FabFormat f : formats) contents.push_back({f, write_fabrication_bytes(layout, f, wo)});
    fs::create_directories(out_dir);
    StagedFiles staged;
    json files = json::array();
    for (const auto& entry : contents) {
        // Not a structured binding: clang 14 (the fuzz/sanitizer build) cannot capture those.
        const FabFormat f = entry.first;
        const std::string& bytes = entry.second;
        const fs::path path = out_dir / (stem + fab_extension(f));
        std::string check = "not readable (written only)";
        staged.stage(path, [&](const fs::path& tmp) {
            {
                std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
                out.write(bytes.data(), std::streamsize(bytes.size()));
                if (!out) throw RuntimeFailure("cannot write " + tmp.string());
            }
            if (is_readable(f)) check = verify(tmp, f, design, layout);
        });
        files.push_back({{"name", path.filename().string()},
                         {"format", fab_format_name(f)},
                         {"units", units_of(f)},
                         {"bytes", bytes.size()},
                         {"fnv1a64", fnv1a64(bytes)},
                         {"verification", check}});
        if (f == FabFormat::kPng) files.back()["dpi"] = o.dpi;
        if (f == FabFormat::kGds) files.back()["layer"] = {o.layer, o.datatype};
        if (f == FabFormat::kDxf) files.back()["layer"] = o.dxf_layer;
    }
    json drc_json = {{"vendor", o.vendor}, {"clean", drc.clean()}, {"counts", drc.counts}};
    json side = {{"format", "pinmask-export"},
                 {"version", 1},
                 {"mask",
                  {{"path", o.input},
                   {"geometry_hash", layout.mask_hash},
                   {"n", mask.pattern.n},
                   {"tiles", {mask.pattern.tiles_rows, mask.pattern.tiles_cols}},
                   {"pinholes", mask.pattern.pinholes.size()},
                   {"pinhole_m", mask.camera.pinhole_m}}},
                 {"geometry",
                  {{"units", "nm (integers), origin at the mask centre, y up"},
                   {"orientation", "mask row 0 at the top (+y), column 0 at the left (-x)"},
                   {"grid_nm", layout.grid_nm},
                   {"tone", tone_name(layout.tone)},
                   {"drawn", layout.tone == Tone::kClear ? "clear areas" : "opaque areas"},
                   {"mirrored", layout.mirrored},
                   {"shape", o.shape},
                   {"sides", layout.hole_sides},
                   {"hole_side_m", lo.hole_side_m > 0 ? lo.hole_side_m : mask.camera.pinhole_m},
                   {"chord_tolerance_m",
                    lo.chord_tolerance_m > 0 ? json(lo.chord_tolerance_m) : json("auto")},
                   {"frame_m", lo.frame_m},
                   {"marks", o.marks},
                   {"label", lo.label_lines},
                   {"max_vertices", lo.max_vertices},
                   {"active_area_nm", box_json(layout.active_area)},
                   {"extent_nm", box_json(layout.extent)},
                   {"polygons", layout.polygons.size()},
                   {"annotations", layout.annotations.size()}}},
                 {"drc", drc_json},
                 {"files", files},
                 {"psf", "not written (--no-psf)"}};
    // The PSF files commit as their own group (cli/psf_files); they are removed again if the
    // fabrication files cannot be committed after them.
    std::vector<fs::path> psf_written;
    if (psf) {
        psf_written =
            io::write_psf_files(out_dir / (stem + ".psf.tiff"), psf->first, psf->second, o.psf_npy);
        json names = json::array();
        for (const fs::path& p : psf_written) names.push_back(p.filename().string());
        side["psf"] = {{"files", names},
                       {"kernel", psf->second.kernel_model},
                       {"pixels_per_cell", psf->second.pixels_per_cell},
                       {"size_px", {psf->first.rows(), psf->first.cols()}}};
    }
    try {
        staged.stage_bytes(out_dir / (stem + ".export.json"), side.dump(2) + "\n");
        staged.commit();
    } catch (...) {
        for (const fs::path& p : psf_written) {
            std::error_code ec;
            fs::remove(p, ec);
        }
        throw;
    }

    if (o.json) {
        std::cout << side.dump(2) << "\n";
        return;
    }
    std::cout << "export of " << o.input << " (hash " << layout.mask_hash << ", tone "
              << tone_name(layout.tone) << (layout.mirrored ? ", mirrored" : "") << ", "
              << layout.polygons.size() << " polygons + " << layout.annotations.size()
              << " annotations) into " << out_dir.string() << "/\n";
    for (const json& f : files)
        std::cout << "  " << f["name"].get<std::string>() << "  " << f["bytes"].get<std::size_t>()
                  << " bytes  " << f["verification"].get<std::string>() << "\n";
    for (const fs::path& p : psf_written) std::cout << "  " << p.filename().string() << "  PSF\n";
    std::cout << "  " << stem << ".export.json  sidecar\n";
    std::cout << "design-rule check (" << o.vendor
              << "): " << (drc.clean() ? "clean" : "violations") << "\n";
    for (const auto& [rule, n] : drc.counts) std::cout << "  " << rule << ": " << n << "\n";
}

void setup(CLI::App& app) {
    auto o = std::make_shared<ExportOptions>();
    auto* cmd = app.add_subcommand(
        "export",
        "Mask file -> fabrication files: SVG (um, 1:1), PDF (1:1 with scale bar), GDSII (1 nm "
        "database unit), DXF R12 (um), Gerber X2 (mm), PNG preview, the PSF (<stem>.psf.tiff + "
        ".json) and <stem>.export.json tying them to the mask hash. Geometry in integer nm, origin "
        "at the mask centre, mask row 0 at "
        "the top. GDS/DXF/Gerber/SVG files are read back and must match the design exactly, "
        "else nothing is written (exit 1).");
    cmd->add_option("input", o->input, "The mask file (*.mask.json)")->required();
    cmd->add_option("-o,--output", o->output, "Output directory (created if missing)")->required();
    cmd->add_option("--format", o->formats,
                    "Comma-separated list of svg, pdf, gds, dxf, gerber, png (default: all)");
    cmd->add_option("--stem", o->stem, "File name stem (default: the mask file name)");
    cmd->add_option("--tone", o->tone,
                    "clear: polygons are the pinholes; dark: polygons are the opaque area "
                    "(outline minus pinholes, split into hole-free pieces). Default clear");
    cmd->add_flag("--mirror", o->mirror,
                  "Mirror about the y axis (right-reading with the chrome/emulsion side down)");
    cmd->add_flag("--marks", o->marks, "Alignment crosses beyond the outline's corners");
    cmd->add_flag("--label", o->label, "Label below the outline: id, geometry hash, scale");
    cmd->add_option("--label-id", o->label_id, "Id on the label (default: the stem)");
    cmd->add_option("--frame", o->frame, "Opaque frame around the active area (length; 0)");
    cmd->add_option("--shape", o->shape, "Pinhole shape: square | circle | polygon (square)");
    cmd->add_option("--sides", o->sides, "Sides of --shape polygon (default 8)");
    cmd->add_option("--hole-side", o->hole_side,
                    "Square side or circle diameter (length; default the cell pitch)");
    cmd->add_option("--chord-tol", o->chord_tol,
                    "Circles: largest sagitta of the inscribed polygon (length), or auto: the "
                    "finest polygon within --max-vertices, no finer than the grid (default auto)");
    cmd->add_option("--grid", o->grid, "Manufacturing grid, whole nm (length; 1nm)");
    cmd->add_option("--max-vertices", o->max_vertices,
                    "Largest vertex count of any polygon: merged and dark-tone pieces are split "
                    "to it, circles drawn within it (default 199)");
    cmd->add_option("--layer", o->layer, "GDSII layer (default 1)");
    cmd->add_option("--datatype", o->datatype, "GDSII datatype (default 0)");
    cmd->add_option("--dxf-layer", o->dxf_layer, "DXF layer name (default PINMASK)");
    cmd->add_option("--dpi", o->dpi, "PNG preview resolution, dots per inch (default 2400)");
    cmd->add_option("--margin", o->margin, "PDF page margin (length; default 10mm)");
    cmd->add_option("--vendor", o->vendor,
                    "Design-rule presets for the report: film | chrome | none (default none)");
    cmd->add_flag("--require-drc-clean", o->require_drc_clean,
                  "Fail (exit 1, no files) when the design-rule check finds violations");
    cmd->add_flag("--allow-spacing-violations", o->allow_spacing_violations,
                  "Read masks that break their spacing rule (touching pinholes are merged)");
    cmd->add_flag("--no-psf", o->no_psf,
                  "Do not write the PSF files (<stem>.psf.tiff and its .json, as `pinmask psf`)");
    cmd->add_flag("--npy", o->psf_npy, "Also write the PSF as <stem>.psf.npy");
    cmd->add_flag("--json", o->json, "Print the sidecar JSON on stdout instead of a table");
    cmd->footer(
        "Example:\n  pinmask export paper.mask.json --format svg,gds,pdf --tone clear --marks "
        "--label --frame 1mm -o out/\n  writes out/paper.svg, out/paper.gds, out/paper.pdf and "
        "out/paper.psf.tiff, out/paper.psf.json and out/paper.export.json");
    cmd->callback([o] { run_export(*o); });
}

const Registration kExport(70, "export", setup);

}  // namespace
}  // namespace pinmask::cli
