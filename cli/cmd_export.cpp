// `pinmask export`: mask file -> fabrication files (export/pipeline/export_pipeline), the PSF files
// (as `pinmask psf` writes them) and the sidecar `<stem>.export.json`, written by io/export_files
// (the transaction Python's export_mask calls too). Every readable file is read back from its
// staged temporary and compared with the design (export/pipeline/read_back); any difference, any
// error and any design-rule violation (unless --write-on-violations) leaves no file. A --vendor
// preset (export/pipeline/vendor_presets) sets defaults that explicit flags override.
#include <filesystem>
#include <iostream>
#include <string>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/export_options.hpp"
#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "design/optics/fab_grid.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/export_files.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using std::string;

// The rules the export checked, in words (vendor preset, overrides and the spacing rule on the
// grid pitch the layout uses).
string rules_line(const ExportOptions& o, const Mask& mask, const Layout& l) {
    return o.drc.name + ": " + vendor_rules_text(o.drc) + ", " +
           spacing_rule_text(mask.pattern.min_spacing_cells, l.pitch_nm, l.grid_nm);
}

// Returns the exit code: 0 clean, 1 the design-rule check found violations (a RuntimeFailure
// from export_mask naming the rules, nothing written; with --write-on-violations the files are
// written for inspection and the exit code is 1 all the same).
int run_export(const ExportFlags& f) {
    if (f.vendor == "list") {
        std::cout << spell_flags(vendor_list_text());
        return 0;
    }
    if (f.input.empty())
        throw invalid_field("input", "''",
                            "a mask file is required (only --vendor list needs none)");
    if (f.output.empty()) throw invalid_field("-o", "''", "an output directory is required");
    const fs::path out_dir = f.output;
    check_output_folder(out_dir, "-o");
    const Mask mask =
        io::read_mask_file(f.input, {.allow_spacing_violations = f.allow_spacing_violations});
    const string stem = f.stem.empty() ? io::default_export_stem(f.input) : f.stem;
    if (stem.empty() || stem.find('/') != string::npos)
        throw invalid_field("--stem", stem, "must be a plain file name");
    const ExportOptions o = export_options_from(f, mask, stem);
    std::vector<NamedPath> outs;  // every output named and checked before any work
    for (const io::ExportOutput& x : io::export_outputs(f, o, out_dir, stem))
        outs.push_back({x.what.empty() ? "-o" : "-o (" + x.what + ")", x.path, true});
    plan_outputs({{"input", f.input}}, outs);
    const io::ExportWritten w = io::write_export(mask, f, o, out_dir, stem);
    const ExportSummary& s = w.summary;
    const io::ExportSidecar& side = w.sidecar;
    const bool clean = s.drc.clean();
    auto verdict = [&] {
        if (clean) return 0;
        std::cerr
            << "pinmask export: the design-rule check (" << rules_line(o, mask, s.layout)
            << ") found violations; the files are written for inspection (--write-on-violations; "
               "`pinmask check "
            << (out_dir / (stem + (s.files.empty() ? "" : s.files.front().extension))).string()
            << "` lists them): exit 1\n";
        return 1;
    };
    if (f.json) {
        std::cout << w.sidecar_text;
        return verdict();
    }
    std::cout << "export of " << f.input << " (hash " << s.layout.mask_hash << ", "
              << tone_words(s.layout.tone) << ", emulsion " << (side.mirrored ? "down" : "up")
              << ", unit " << side.unit << ", " << s.layout.polygons.size() << " polygons + "
              << s.layout.annotations.size() << " annotations) into " << out_dir.string() << "/\n";
    for (const io::ExportSidecarFile& e : side.files)
        std::cout << "  " << e.name << "  " << e.bytes << " bytes  " << e.verification << "\n";
    for (const fs::path& p : w.psf) std::cout << "  " << p.filename().string() << "  PSF\n";
    std::cout << "  " << stem << ".export.json  sidecar\n";
    for (const string& n : s.notes) std::cout << "note: " << spell_flags(n) << "\n";
    std::cout << "design-rule check (" << rules_line(o, mask, s.layout)
              << "): " << (clean ? "clean" : "VIOLATIONS") << "\n";
    for (const auto& [rule, n] : s.drc.counts) std::cout << "  " << rule << ": " << n << "\n";
    constexpr std::size_t kListed = 5;  // the first few, in the check's words
    for (std::size_t i = 0; i < s.drc.violations.size() && i < kListed; ++i)
        std::cout << "    " << drc_rule_name(s.drc.violations[i].rule) << ": "
                  << s.drc.violations[i].message << "\n";
    return verdict();
}

void setup(CLI::App& app, int& exit_code) {
    auto f = std::make_shared<ExportFlags>();
    auto* c = app.add_subcommand(
        "export",
        "Mask file -> fabrication files: SVG, PDF, GDSII, OASIS, DXF R12, Gerber X2, PNG preview, "
        "1-bit plotter TIFF, the PSF (<stem>.psf.tiff + .json) and <stem>.export.json. Geometry "
        "in integer nm, origin at the mask centre, mask row 0 at the top. GDS/OASIS/DXF/Gerber/SVG "
        "files are read back and must match the design exactly, else nothing is written (exit 1).");
    c->add_option("input", f->input, "The mask file (*.mask.json); not with --vendor list");
    c->add_option("-o,--output", f->output, "Output directory (created if missing)");
    c->add_option("--format", f->formats,
                  "Comma-separated svg, pdf, gds, oasis, dxf, gerber, png, tiff1 (default: svg, "
                  "pdf, gds, dxf, gerber, png)");
    c->add_option("--stem", f->stem, "File name stem (default: the mask file name)");
    c->add_option("--vendor", f->vendor,
                  "Preset: chrome-photomask | film-plotter | gerber-film | laser-cutter (formats, "
                  "units, tone, side, frame, grid...; flags win), or rules only: film | chrome | "
                  "none. `--vendor list` prints them")
        ->capture_default_str();
    c->add_option("--units", f->units,
                  "DXF drawing unit and GDSII/OASIS user unit: um | mm | in (default um; Gerber "
                  "is always mm, SVG/PDF physical)");
    c->add_option("--tone", f->tone,
                  "clear (alias negative): polygons are the clear pinholes; dark (alias positive): "
                  "polygons are the opaque film (default clear)");
    c->add_option("--emulsion", f->emulsion,
                  "up: right-reading from the emulsion side; down: mirrored, right-reading "
                  "through the base (= --mirror). Default up");
    c->add_flag("--mirror", f->mirror, "Mirror about the y axis (= --emulsion down)");
    c->add_option("--draw", f->draw,
                  "PDF/PNG/SVG: film (as the film looks) | polygons (the drawn polygons black on "
                  "white, e.g. opaque pinholes). Default: film for PDF and PNG, polygons for SVG");
    c->add_option("--circles", f->circles,
                  "Round pinholes in DXF/Gerber: native (CIRCLE, circular flashes) | polygon "
                  "(default polygon)");
    c->add_option("--hierarchy", f->hierarchy,
                  "GDSII: flat | cells (one pinhole cell, SREF per pinhole, AREF over repeating "
                  "tiles) | auto (cells above 10000 pinholes)")
        ->capture_default_str();
    c->add_flag("--marks", f->marks, "Alignment crosses beyond the outline's corners");
    c->add_flag("--label", f->label, "Label: id, hash, scale, tone, emulsion side, unit");
    c->add_option("--label-id", f->label_id, "Id on the label (default: the stem)");
    c->add_option("--frame", f->frame, "Opaque frame around the active area (length; 0)");
    c->add_option("--shape", f->shape, "Pinhole shape: square | circle | polygon")
        ->capture_default_str();
    c->add_option("--sides", f->sides, "Sides of --shape polygon (default 8)");
    c->add_option("--hole-side", f->hole_side,
                  "Square side or circle diameter (length > 0; default the cell pitch)");
    c->add_option("--kerf", f->kerf, "Laser kerf: holes drawn this much smaller (length; 0)");
    c->add_option("--chord-tol", f->chord_tol,
                  "Circles: largest sagitta of the polygon (length), or auto")
        ->capture_default_str();
    c->add_option("--grid", f->grid,
                  "Manufacturing grid, whole nm (length; default the vendor's, else 1nm). The "
                  "pinhole side is snapped to it once: every cell edge is a whole number of "
                  "pitches on the grid");
    c->add_option("--min-feature", f->min_feature,
                  "The shop's minimum feature width (length, e.g. 2um), over the vendor's rules");
    c->add_option("--min-space", f->min_space,
                  "The shop's minimum space between polygons (length, e.g. 2um; >= 1 nm), over "
                  "the vendor's rules");
    c->add_option("--max-vertices", f->max_vertices, "Vertex limit per polygon (default 199)");
    c->add_option("--layer", f->layer, "GDSII/OASIS layer")->capture_default_str();
    c->add_option("--datatype", f->datatype, "GDSII/OASIS datatype")->capture_default_str();
    c->add_option("--dxf-layer", f->dxf_layer, "DXF layer name")->capture_default_str();
    c->add_option("--dpi", f->dpi,
                  "Raster resolution in dots per inch (PNG default 2400, tiff1 default 25400)");
    c->add_option("--max-snap-error", f->max_snap_error,
                  "tiff1: refuse when snapping to the plotter grid moves an edge more (length)");
    c->add_option("--margin", f->margin, "PDF page margin (length)")->capture_default_str();
    c->add_flag("--require-drc-clean", f->require_drc_clean,
                "Fail (exit 1, no files) when the design-rule check finds violations: the "
                "default, kept for scripts that give it");
    c->add_flag("--write-on-violations", f->write_on_violations,
                "Write the files even when the design-rule check finds violations, for "
                "inspection (the violations are listed and the exit code is 1 all the same)");
    c->add_flag("--allow-spacing-violations", f->allow_spacing_violations,
                "Read masks that break their spacing rule (touching pinholes are merged)");
    c->add_flag("--no-psf", f->no_psf, "Do not write the PSF files");
    c->add_flag("--npy", f->psf_npy, "Also write the PSF as <stem>.psf.npy");
    c->add_flag("--json", f->json, "Print the sidecar JSON on stdout instead of a table");
    c->footer(kExportFooter);
    c->callback([f, &exit_code] { exit_code = run_export(*f); });
}

}  // namespace

void add_export(CLI::App& app, int& exit_code) { setup(app, exit_code); }
}  // namespace pinmask::cli
