// `pinmask check`: the design-rule check (export/pipeline/drc) of a mask file, via the layout the
// export builds from it, or of a fabrication file read back (GDSII, OASIS, DXF, Gerber, SVG) or a
// picture (PDF, PNG, 1-bit TIFF) compared with its design: the transaction io/check_files, which
// Python's check() calls too, rendered by io/check_json for --json. The layout settings come
// from the export sidecar <stem>.export.json beside the file when there is one (explicit flags
// must agree with it), else from the flags. What identifies the film (layer, datatype, DXF layer
// name, Gerber polarity) is compared with the sidecar or the vendor preset
// (export/pipeline/film_identity). Exit codes: 0 clean, 1 violations (or an XOR or film identity
// mismatch), 2 bad input, 3 the time limit PINMASK_TIME_LIMIT was spent (no verdict printed:
// check writes only stdout, at the end).
#include <iostream>
#include <memory>
#include <string>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/check_settings.hpp"
#include "cli/outputs/check_report.hpp"
#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "io/check_files.hpp"
#include "io/check_json.hpp"

namespace pinmask::cli {
namespace {

// Returns the exit code: 0 clean, 1 violations found.
int run(const CheckOptions& o) {
    const TimeLimitScope time_limited;  // the readers and the DRC poll it too
    check_time_limit("check stopped before reading " + o.input);
    validate(o);
    io::CheckRequest q;
    q.input = o.input;
    q.mask = o.mask;
    q.vendor = o.vendor;
    q.overrides = [&o](DrcRules r) { return resolve_rules(o, r); };
    q.spacing_given = o.min_spacing.has_value();
    q.max_xor_um2 = o.max_xor_um2;
    q.layout = o.layout;
    q.no_sidecar = o.no_sidecar;
    q.list = o.list;
    const io::CheckReport rep = io::run_check(q);
    if (!rep.unit_assumed.empty()) std::cerr << "pinmask: warning: " << rep.unit_assumed << "\n";
    if (o.json)
        std::cout << io::check_json(rep).dump() << "\n";
    else
        print_check_text(rep);
    return rep.check.clean() ? 0 : 1;
}

void setup(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<CheckOptions>();
    auto* cmd = app.add_subcommand(
        "check", "Design-rule check of a mask file or an exported fabrication file.");
    cmd->footer(kCheckFooter);
    cmd->add_option("input", o->input,
                    "A *.mask.json, or a .gds/.oas/.dxf/.gbr/.svg/.pdf/.png/.tif file")
        ->required();
    cmd->add_option("--vendor", o->vendor,
                    "Process limits: a preset of `export --vendor` (chrome-photomask, "
                    "film-plotter, ...) or rules film (features and gaps >= 16 um, 20000 dpi "
                    "plotter), chrome (>= 1 um), none (polygons must only not touch); all: <= 199 "
                    "vertices. Default: the rules the export sidecar records (vendor and any "
                    "--min-feature/--min-space given to export), else film");
    cmd->add_option("--min-space,--min-gap", o->min_gap,
                    "Override the minimum space (gap) between polygons (length, e.g. 2um; "
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
    cmd->add_option("--shape", o->layout.shape,
                    "Design pinhole shape: square | circle | polygon (default square)");
    cmd->add_option("--sides", o->layout.sides,
                    "Design polygon sides (--shape polygon; default 8)");
    cmd->add_option("--tone", o->layout.tone,
                    "Design tone: clear | dark (aliases negative | positive)");
    cmd->add_flag("--mirror", o->layout.mirror, "Design mirrored (emulsion down)");
    cmd->add_option("--units", o->layout.units, "Unit the file was exported in: um | mm | in");
    cmd->add_flag("--no-sidecar", o->no_sidecar,
                  "Ignore <stem>.export.json beside the file (settings from the flags only)");
    cmd->add_option("--hole-side", o->layout.hole_side,
                    "Design pinhole side / diameter (length; default: the cell pitch)");
    cmd->add_option("--frame", o->layout.frame, "Design opaque frame width (length; default 0)");
    cmd->add_option("--chord-tol", o->layout.chord_tol,
                    "Design circle chord tolerance (length; default 10nm, as export)");
    cmd->add_option("--list", o->list, "Violations listed per rule (all are counted)")
        ->capture_default_str();
    cmd->add_flag("--json", o->json,
                  "Print {clean, design_rules_checked (false for vendor none), input, kind, "
                  "vendor, tone, polygons, annotations, rules, "
                  "measured, counts, truncated, violations: [{rule, message, x_um, y_um, "
                  "polygon_a, polygon_b, value, limit, unit}], comparison} on stdout");
    cmd->callback([o, &exit_code] {
        try {
            exit_code = run(*o);
        } catch (const TimeLimitSpent& e) {
            throw TimeLimitSpent(std::string(e.what()) + "; no verdict (exit code 3)");
        }
    });
}

}  // namespace

void add_check(CLI::App& app, int& exit_code) { setup(app, exit_code); }
}  // namespace pinmask::cli
