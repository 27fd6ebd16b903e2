// `pinmask design`: the optics report (docs/design.md section 2) for a preset or explicit
// parameters, as a table (quantity, value, note) or, with --json, one JSON object whose keys carry
// units. Infinite values (z_eff at f = f', the pinhole for integer pixels when M = 0, u = inf) are
// written as JSON null with the reason under "notes" (key -> text).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/command_flags.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/design_report.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "design/optics/default_pinhole.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/packing_bound.hpp"
#include "design/psf/design_kernel.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_validity.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/camera_json.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {
namespace {

struct DesignOptions {
    CameraOptions camera;
    GeometryOptions geometry;
    std::string kernel = "auto";
    double lsi_tolerance_px = 1.0;
    std::optional<int> pixels_per_cell;   // solve the pinhole for N whole pixels per cell at u
    std::string solve;                    // "pinhole": N = the nearest whole number at u
    std::string save_camera;              // write the resolved (solved) camera here
    std::optional<std::string> fab_grid;  // a solved pinhole lands on this grid (default 1nm)
    std::optional<std::string> vendor;    // ... or on this export preset's grid
    bool json = false;
};

// The fabrication grid a solved pinhole is snapped to: --fab-grid, else the --vendor preset's,
// else 1 nm.
GridSnap fab_grid_of(const DesignOptions& o) {
    GridSnap g;
    if (o.fab_grid && o.vendor)
        throw invalid_field("--fab-grid", *o.fab_grid,
                            "and --vendor both set the grid: give one of them");
    if (o.fab_grid) {
        g.grid_nm = fab_grid_nm(parse_length_m(*o.fab_grid, "--fab-grid"), "--fab-grid");
        g.grid_source = "--fab-grid";
    } else if (o.vendor) {
        const VendorPreset* p = find_vendor_preset(*o.vendor);
        if (!p)
            throw invalid_field("--vendor", *o.vendor,
                                "is a rule preset without a grid; give an export preset "
                                "(`pinmask export --vendor list`) or --fab-grid");
        g.grid_nm = fab_grid_nm(p->grid_m, "--vendor");
        g.grid_source = "vendor " + p->name;
    } else {
        g.grid_nm = kDefaultFabGridNm;
        g.grid_source = "default";
    }
    return g;
}

PatternGeometry resolve_geometry(const GeometryOptions& g) {
    if (g.grid < 1 || g.grid > kMaxGrid) {
        throw invalid_field("--grid", std::to_string(g.grid),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    const long long cells = static_cast<long long>(g.grid) * g.grid;
    if (g.holes < 0 || g.holes > cells) {
        throw invalid_field("--holes", std::to_string(g.holes),
                            "must be between 0 and n^2 = " + std::to_string(cells));
    }
    if (g.tiles < 1 || g.tiles > kMaxTiles)
        throw invalid_field("--tiles", std::to_string(g.tiles),
                            "must be between 1 and " + std::to_string(kMaxTiles));
    if (!std::isfinite(g.spacing) || g.spacing < 0) {
        throw invalid_field("--spacing", std::to_string(g.spacing), "must be finite and >= 0");
    }
    return {g.grid, g.holes, g.tiles, g.tiles};
}

void run(const DesignOptions& o, const CLI::App& command) {
    // --pixels-per-cell solves the pinhole itself: no default pinhole is chosen (or said) first.
    CameraOptions camera_options = o.camera;
    camera_options.default_pinhole = !o.pixels_per_cell;
    Camera camera = resolve_camera(camera_options);
    const PatternGeometry geometry = resolve_geometry(o.geometry);
    const KernelModel kernel = parse_kernel_model(o.kernel, "--kernel");
    validate_lsi_tolerance(o.lsi_tolerance_px);  // design/optics/optics: the range, both faces
    if (!o.save_camera.empty()) {
        const std::filesystem::path out(o.save_camera), dir = out.parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir)) {
            throw invalid_field("--save-camera", o.save_camera, "its folder does not exist");
        }
        if (o.camera.camera_file && std::filesystem::exists(out) &&
            std::filesystem::equivalent(out, *o.camera.camera_file)) {
            throw invalid_field("--save-camera", o.save_camera,
                                "is the --camera input: refusing to overwrite an input");
        }
    }
    if (!o.solve.empty() && o.solve != "pinhole") {
        throw invalid_field("--solve", o.solve, "must be 'pinhole'");
    }
    if (o.pixels_per_cell && o.camera.pinhole) {
        throw invalid_field("--pixels-per-cell", std::to_string(*o.pixels_per_cell),
                            "solves the pinhole side, so it cannot be given with --pinhole too");
    }
    if (o.pixels_per_cell && (*o.pixels_per_cell < 1 || *o.pixels_per_cell > kMaxPixelsPerCell)) {
        throw invalid_field("--pixels-per-cell", std::to_string(*o.pixels_per_cell),
                            "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
    }
    check_object_distance(camera, camera.object_distance_m, "--object-distance");
    GridSnap snap = fab_grid_of(o);
    if ((o.fab_grid || o.vendor) && !o.pixels_per_cell && o.solve.empty())
        throw invalid_field(o.fab_grid ? "--fab-grid" : "--vendor",
                            o.fab_grid ? *o.fab_grid : *o.vendor,
                            "sets the grid a solved pinhole lands on: use it with --solve pinhole "
                            "or --pixels-per-cell");
    WorkingDistanceOptions wo{o.lsi_tolerance_px, o.pixels_per_cell.value_or(0)};
    std::string solved;
    if (o.pixels_per_cell || !o.solve.empty()) {
        // --solve pinhole keeps the whole pitch of the pinhole it starts from: a start far from
        // the optimum gives a solution as far from it, so the optimum is said.
        if (!o.pixels_per_cell) {
            const std::string far = far_from_optimum_note(camera);
            if (!far.empty())
                std::cerr << "pinmask: warning: " << spell_flags(far, command) << "\n";
        }
        const WorkingDistance start = compute_working_distance(camera, geometry, wo);
        if (start.pixels_per_cell > kMaxPixelsPerCell) {
            throw invalid_field("--solve", "pinhole",
                                "the pitch at u is " + std::to_string(start.pixels_per_cell) +
                                    " px per cell, above the " + std::to_string(kMaxPixelsPerCell) +
                                    " px limit");
        }
        // d for exactly N at u, then on the fabrication grid (what export draws).
        snap.exact_m = pinhole_for_pixels_per_cell(camera, start.pixels_per_cell);
        if (const std::string big = solved_pinhole_too_large(snap.exact_m, start.pixels_per_cell);
            !big.empty())
            throw invalid_field(o.pixels_per_cell ? "--pixels-per-cell" : "--solve",
                                o.pixels_per_cell ? std::to_string(*o.pixels_per_cell) : "pinhole",
                                big);
        snap.on_grid_m = pinhole_on_grid_m(snap.exact_m, snap.grid_nm);
        snap.solved = true;
        camera.pinhole_m = snap.on_grid_m;
        snap.pitch_shift_px = pixels_per_cell_at(camera, camera.object_distance_m) -
                              static_cast<double>(start.pixels_per_cell);
        wo.pixels_per_cell = static_cast<int>(start.pixels_per_cell);
        solved = "solved: d gives N at u, then snapped to the fabrication grid";
    }
    OpticsReport r = compute_optics(camera, geometry, kernel, {o.lsi_tolerance_px});
    const WorkingDistance wd = compute_working_distance(camera, geometry, wo);
    // The kernel psf would build for this design (its band, the model over the band, the energy
    // its support keeps), so design warns where psf would.
    DesignKernel dk = design_kernel(camera, geometry.n, wd.pixels_per_cell, o.kernel);
    if (dk.kernel) {
        r.kernel_model = dk.kernel->model;
        r.kernel_reason = dk.kernel->model_reason;
    }
    KernelValidity& validity = dk.validity;
    for (auto& w : validity.warnings) w = spell_flags(w, command);
    if (!validity.model_accurate) r.kernel_reason = "NOT accurate: " + validity.warnings.front();
    for (const auto& w : validity.warnings) std::cerr << "pinmask: warning: " << w << "\n";
    std::vector<CameraInput> inputs = camera_inputs(camera_options, camera);
    if (!solved.empty())
        inputs[0].source = "solved for N px per cell at u, on the " + std::to_string(snap.grid_nm) +
                           " nm fabrication grid";
    // The spacing rule against the pinhole count: the proven packing bound
    // (design/pattern/packing_bound), so a design that no search or generator can realise says so
    // before any of them runs.
    const PackingUpperBound most = packing_upper_bound(geometry.n, o.geometry.spacing);
    if (geometry.holes > most.count)
        std::cerr << "pinmask: warning: --holes " << geometry.holes
                  << ": that many pinholes do not fit on a " << geometry.n << " x " << geometry.n
                  << " grid at --spacing " << o.geometry.spacing << ": at most " << most.count
                  << " (" << most.reason << ")\n";
    if (!o.save_camera.empty()) io::write_camera_file(o.save_camera, camera);
    if (o.json) {
        auto j = design_json(r, wd, snap, dk);
        j["spacing_cells"] = o.geometry.spacing;
        j["max_holes_at_spacing"] = most.count;
        j["max_holes_reason"] = most.reason;
        j["kernel_warnings"] = validity.warnings;
        for (const CameraInput& in : inputs) j["input_sources"][in.symbol] = in.source;
        std::cout << io::json_strict::pretty(j) << "\n";
    } else {
        std::cout << design_table(r, wd, solved, inputs, snap, dk);
        if (!o.save_camera.empty()) std::cerr << "wrote " << o.save_camera << "\n";
    }
}

constexpr const char* kFooter =
    "Every figure is at the working distance u (--object-distance; a point source at u: "
    "1/z_eff = 1/f - 1/f' + 1/u): pitch, whole pixels per cell N, PSF size n N, periods on the "
    "sensor, LSI mismatch against N; the indented \"u = inf\" lines are the distant-object "
    "values the paper quotes. A solved pinhole (--solve pinhole, --pixels-per-cell) lands on the "
    "fabrication grid (--fab-grid, or the --vendor preset's, default 1nm) and the table says how "
    "far that moves the pitch at u. --json prints one object with unit-suffixed keys (_m = "
    "metres, _px = pixels): keys without a suffix and \"_at_u\" keys are at u, \"_at_inf\" "
    "keys at u = inf; infinite values are null, with the reason under \"notes\". The kernel row "
    "is the kernel psf would build at N px per cell over the band (--bandwidth: a Gaussian of "
    "that FWHM at 13 wavelengths), with the energy its support keeps; its warnings are psf's.\n"
    "Examples:\n"
    "  pinmask design --preset paper\n"
    "  pinmask design --lens-focal 55mm --object-distance inf --json   (f = f': Fraunhofer)\n"
    "  pinmask design --pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm \\\n"
    "      --sensor-distance 20mm --object-distance 2m --wavelength 530nm --pixels-per-cell 21\n"
    "      (solves d = 345 um for 21 whole pixels per cell at 2 m)\n"
    "  pinmask design --wavelength 850nm --bandwidth 30nm   (an LED's 30 nm band around 850 nm)";

void setup(CLI::App& app) {
    auto o = std::make_shared<DesignOptions>();
    auto* cmd = app.add_subcommand(
        "design",
        "Optics report: spot size, pixels per cell, Fresnel numbers, effective distance, "
        "shift-invariance range, PSF size and the kernel model, for a preset or explicit "
        "parameters.");
    cmd->footer(kFooter);
    add_camera_options(*cmd, o->camera);
    add_geometry_options(*cmd, o->geometry);
    cmd->add_option("--kernel", o->kernel,
                    "Kernel model to report: " + kernel_model_names() +
                        " (auto: chosen from the Fresnel number with the lens at u)")
        ->capture_default_str();
    cmd->add_option("--lsi-tolerance", o->lsi_tolerance_px,
                    "Shift-invariance tolerance in pixels across the widest pinhole separation "
                    "of one period (s_max = n d): sets the usable object-distance range around u "
                    "and the LSI min object distance")
        ->capture_default_str();
    cmd->add_option("--pixels-per-cell", o->pixels_per_cell,
                    "Solve the pinhole side d for this whole number N of pixels per cell AT the "
                    "object distance u: d = N w / |1 - f/f' + f/u| (not with --pinhole)");
    cmd->add_option("--solve", o->solve,
                    "pinhole: solve d for the whole number of pixels per cell nearest to the "
                    "pitch at u of the given (or preset) pinhole")
        ->check(CLI::IsMember({"pinhole"}));
    cmd->add_option("--save-camera", o->save_camera,
                    "Write the camera used (with a solved pinhole) as a *.camera.json file, for "
                    "--camera FILE of any command");
    cmd->add_option("--fab-grid", o->fab_grid,
                    "Fabrication grid a solved pinhole lands on (length, whole nm; default 1nm; "
                    "export draws every cell edge on it)");
    cmd->add_option("--vendor", o->vendor,
                    "Export preset whose grid a solved pinhole lands on (e.g. film-plotter: "
                    "1 um; `pinmask export --vendor list`)");
    cmd->add_flag("--json", o->json, "Print the report as one JSON object on stdout");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_design(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
