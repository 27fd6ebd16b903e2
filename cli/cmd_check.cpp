// `pinmask check`: the design-rule check (export/pipeline/drc) of a mask file, via the layout the
// export builds from it, or of a fabrication file read back (GDSII, OASIS, DXF, Gerber, SVG) and
// compared with its design (export/pipeline/check_run, which Python calls too). The layout
// settings come from the export sidecar <stem>.export.json beside the file when there is one
// (explicit flags must agree with it), else from the flags. What identifies the film (layer,
// datatype, DXF layer name, Gerber polarity) is compared with the sidecar or the vendor preset
// (export/pipeline/film_identity). Exit codes: 0 clean, 1 violations (or an XOR or film identity
// mismatch), 2 bad input, 3 the time limit PINMASK_TIME_LIMIT was spent (no verdict printed:
// check writes only stdout, at the end).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/check_settings.hpp"
#include "cli/outputs/check_picture.hpp"
#include "cli/outputs/check_report.hpp"
#include "core/errors/error.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/fab_units.hpp"
#include "export/formats/read_any.hpp"
#include "export/layout/vendor_rules.hpp"
#include "export/pipeline/check_run.hpp"
#include "io/export_sidecar.hpp"
#include "io/mask_json.hpp"
#include "io/sidecar_identity.hpp"
#include "io/sidecar_layout.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

// Between the stages of a check: the time budget (PINMASK_TIME_LIMIT), if spent, stops it.
void poll_time(const std::string& stage) { check_time_limit("check stopped " + stage); }

// Returns the exit code: 0 clean, 1 violations found.
int run(const CheckOptions& o) {
    const TimeLimitScope time_limited;  // the readers and the DRC poll it too
    poll_time("before reading " + o.input);
    validate(o);
    const bool mask_input = io::is_mask_file(o.input);
    // The export sidecar beside a fabrication file gives the vendor's rules (and the layout).
    const fs::path side_path = io::sidecar_path_for(o.input);
    std::optional<io::ExportSidecar> side;
    if (!mask_input && !o.no_sidecar && fs::is_regular_file(side_path))
        side = io::read_export_sidecar(side_path);
    std::string rules_source;
    const VendorRules vendor = check_vendor_rules(o, side ? &*side : nullptr, rules_source);
    CheckReport rep;  // fields assigned: a partial designated initializer warns (-Wextra)
    rep.input = o.input;
    rep.vendor = vendor.name;
    rep.mask = o.mask;
    rep.list = o.list;
    rep.rules_source = rules_source;
    const RuleOverrides overrides = [&o](DrcRules r) { return resolve_rules(o, r); };
    FileCheck c;
    if (const auto picture = picture_format_of(o.input); picture && !mask_input) {
        rep.kind = fab_format_name(*picture);
        c = check_picture(o, vendor, rep);
    } else if (mask_input) {
        if (!o.mask.empty())
            throw invalid_field("--mask", o.mask, "only used with a fabrication file");
        rep.kind = "mask";
        const Mask mask = io::read_mask_file(o.input, {.allow_spacing_violations = true});
        CheckRun run = check_mask(mask, design_options(o, nullptr), vendor, overrides, o.input);
        c = std::move(run.check);
        rep.rules = run.rules;
        if (!o.min_spacing) rep.spacing = run.spacing;
    } else {
        rep.kind = fs::path(o.input).extension().string().substr(1);
        const FileGeometry file = read_fabrication_file(o.input);
        poll_time("after reading " + o.input);
        if (side) {
            rep.settings = "from " + side_path.string();
            if (rep.mask.empty()) rep.mask = io::sidecar_mask(*side, side_path);
            io::check_sidecar_unit(*side, file);
        } else {
            rep.settings = "from the flags (no sidecar " + side_path.filename().string() + ")";
        }
        FabricationCheckRequest q;
        q.input = o.input;
        q.vendor = vendor;
        q.overrides = overrides;
        q.max_xor_nm2 = o.max_xor_um2 * 1e6;
        std::optional<Mask> mask;
        if (!rep.mask.empty()) {
            mask = io::read_mask_file(rep.mask, {.allow_spacing_violations = true});
            q.layout = design_options(o, side ? &*side : nullptr);
            if (!side) io::apply_file_declarations(q.layout, file);  // as the file declares them
            q.mask = &*mask;
            q.whole_layout = side.has_value();
        } else {
            // No design to build, but the flags given are still checked, and compared with the
            // sidecar: a contradiction stops the check whether or not its mask resolves.
            (void)design_options(o, side ? &*side : nullptr);
            if (side) {
                const auto& a = side->active_area_nm;
                const std::int64_t fr = std::llround(side->frame_m * 1e9);
                q.outline = BoxNm{a[0] - fr, a[1] - fr, a[2] + fr, a[3] + fr};
                rep.note = "mask " + side->mask_path +
                           " not found: no comparison; centre spacing only with --min-spacing";
            } else {
                rep.note =
                    "no --mask and no sidecar: all rings are checked as polygons; centre "
                    "spacing only with --min-spacing";
            }
        }
        q.film = io::film_identity_expected(o.input, side ? &*side : nullptr, side_path,
                                            o.no_sidecar, o.vendor, o.layout.tone);
        CheckRun run = check_fabrication(file, q);
        c = std::move(run.check);
        rep.rules = run.rules;
        if (mask && !o.min_spacing) rep.spacing = run.spacing;
        if (!run.unit_assumed.empty() && !side) {
            std::cerr << "pinmask: warning: " << run.unit_assumed << "\n";
            rep.note = rep.note.empty() ? run.unit_assumed : rep.note + "; " + run.unit_assumed;
        }
    }
    poll_time("before printing the verdict on " + o.input);
    rep.check = &c;
    if (o.json)
        print_check_json(rep);
    else
        print_check_text(rep, vendor);
    return c.clean() ? 0 : 1;
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
