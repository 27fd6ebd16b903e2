// `pinmask design`: the optics report (docs/design.md section 2) for a preset or explicit
// parameters: parses and checks the flags, runs design/optics/design_run, prints a table
// (quantity, value, note) or, with --json, io/design_json's object whose keys carry units. Infinite
// values (z_eff at f = f', the pinhole for integer pixels when M = 0, u = inf) are written as JSON
// null with the reason under "notes" (key -> text).
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/command_flags.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/design_report.hpp"
#include "core/errors/error.hpp"
#include "core/units/units.hpp"
#include "design/optics/design_run.hpp"
#include "design/optics/fab_grid.hpp"
#include "export/pipeline/vendor_presets.hpp"
#include "io/camera_json.hpp"
#include "io/design_json.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {
namespace {

struct DesignOptions {
    CameraOptions camera;
    GeometryOptions geometry;
    std::string kernel = DesignRequest{}.kernel;
    double lsi_tolerance_px = DesignRequest{}.lsi_tolerance_px;
    std::optional<int> pixels_per_cell;   // solve the pinhole for N whole pixels per cell at u
    std::string solve;                    // "pinhole": N = the nearest whole number at u
    std::string save_camera;              // write the resolved (solved) camera here
    std::optional<std::string> fab_grid;  // a solved pinhole lands on this grid (default 1nm)
    std::optional<std::string> vendor;    // ... or on this export preset's grid
    bool json = false;
};

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
    DesignRequest q;
    q.camera = camera;
    q.geometry = geometry;
    q.spacing_cells = o.geometry.spacing;
    q.model = kernel;
    q.kernel = o.kernel;
    q.lsi_tolerance_px = o.lsi_tolerance_px;
    if (o.pixels_per_cell) q.pixels_per_cell = static_cast<int>(*o.pixels_per_cell);
    q.solve = !o.solve.empty();
    // The grid a solved pinhole lands on: --fab-grid, or the --vendor export preset's
    // (design/optics/design_run checks them).
    if (o.fab_grid) {
        q.fab_grid_m = parse_length_m(*o.fab_grid, "--fab-grid");
        q.fab_grid_text = *o.fab_grid;
    }
    if (o.vendor) {
        q.vendor = *o.vendor;
        if (const VendorPreset* p = find_vendor_preset(*o.vendor)) q.vendor_grid_m = p->grid_m;
    }
    for (const CameraInput& in : camera_inputs(camera_options, camera))
        q.input_sources.emplace_back(in.symbol, in.source);
    q.spell = [&command](const std::string& w) { return spell_flags(w, command); };
    const DesignReport d = run_design_request(q);
    if (!d.far_from_optimum.empty())
        std::cerr << "pinmask: warning: " << d.far_from_optimum << "\n";
    for (const auto& w : d.kernel.validity.warnings) std::cerr << "pinmask: warning: " << w << "\n";
    const std::string solved =
        d.snap.solved ? "solved: d gives N at u, then snapped to the fabrication grid" : "";
    std::vector<CameraInput> inputs = camera_inputs(camera_options, d.camera);
    for (std::size_t i = 0; i < inputs.size(); ++i) inputs[i].source = d.input_sources[i].second;
    if (geometry.holes > d.packing.count)
        std::cerr << "pinmask: warning: --holes " << geometry.holes
                  << ": that many pinholes do not fit on a " << geometry.n << " x " << geometry.n
                  << " grid at --spacing " << o.geometry.spacing << ": at most " << d.packing.count
                  << " (" << d.packing.reason << ")\n";
    if (!o.save_camera.empty()) io::write_camera_file(o.save_camera, d.camera);
    if (o.json) {
        std::cout << io::json_strict::pretty(io::design_json(d)) << "\n";
    } else {
        std::cout << design_table(d.optics, d.working, solved, inputs, d.snap, d.kernel);
        if (!o.save_camera.empty()) std::cerr << "wrote " << o.save_camera << "\n";
    }
}

void setup(CLI::App& app) {
    auto o = std::make_shared<DesignOptions>();
    auto* cmd = app.add_subcommand(
        "design",
        "Optics report: spot size, pixels per cell, Fresnel numbers, effective distance, "
        "shift-invariance range, PSF size and the kernel model, for a preset or explicit "
        "parameters.");
    cmd->footer(kDesignFooter);
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
