// `pinmask design`: the optics report (DESIGN.md section 1) for a preset or explicit parameters,
// as a table (quantity, value, note) or, with --json, one JSON object whose keys carry units.
// Infinite values (z_eff at f = f', the pinhole for integer pixels when M = 0, u = inf) are
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

#include "cli/options/camera_options.hpp"
#include "cli/commands.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/design_report.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "design/kernel.hpp"
#include "design/kernel_validity.hpp"
#include "design/optics.hpp"
#include "design/working_distance.hpp"
#include "io/camera_json.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {
namespace {

struct DesignOptions {
    CameraOptions camera;
    GeometryOptions geometry;
    std::string kernel = "auto";
    double lsi_tolerance_px = 1.0;
    std::optional<int> pixels_per_cell;  // solve the pinhole for N whole pixels per cell at u
    std::string solve;                   // "pinhole": N = the nearest whole number at u
    std::string save_camera;             // write the resolved (solved) camera here
    bool json = false;
};

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
    if (g.tiles < 1) throw invalid_field("--tiles", std::to_string(g.tiles), "must be >= 1");
    if (!std::isfinite(g.spacing) || g.spacing < 0) {
        throw invalid_field("--spacing", std::to_string(g.spacing), "must be finite and >= 0");
    }
    return {g.grid, g.holes, g.tiles, g.tiles};
}

void run(const DesignOptions& o) {
    Camera camera = resolve_camera(o.camera);
    const PatternGeometry geometry = resolve_geometry(o.geometry);
    const KernelModel kernel = parse_kernel_model(o.kernel, "--kernel");
    if (!(o.lsi_tolerance_px > 0) || !std::isfinite(o.lsi_tolerance_px)) {
        throw invalid_field("--lsi-tolerance", std::to_string(o.lsi_tolerance_px),
                            "must be finite and > 0 (0 or less gives an empty object-distance "
                            "range)");
    }
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
    WorkingDistanceOptions wo{o.lsi_tolerance_px, o.pixels_per_cell.value_or(0)};
    std::string solved;
    if (o.pixels_per_cell || !o.solve.empty()) {
        const WorkingDistance start = compute_working_distance(camera, geometry, wo);
        if (start.pixels_per_cell > kMaxPixelsPerCell) {
            throw invalid_field("--solve", "pinhole",
                                "the pitch at u is " + std::to_string(start.pixels_per_cell) +
                                    " px per cell, above the " + std::to_string(kMaxPixelsPerCell) +
                                    " px limit");
        }
        camera.pinhole_m = pinhole_for_pixels_per_cell(camera, start.pixels_per_cell);
        wo.pixels_per_cell = static_cast<int>(start.pixels_per_cell);
        solved = "solved: the pinhole d above is set to give exactly N at u";
    }
    OpticsReport r = compute_optics(camera, geometry, kernel, {o.lsi_tolerance_px});
    KernelValidity validity = kernel_validity(camera, r.kernel_model);  // never "accurate"
    for (auto& w : validity.warnings) w = spell_flags(w);
    if (!validity.model_accurate) r.kernel_reason = "NOT accurate: " + validity.warnings.front();
    for (const auto& w : validity.warnings) std::cerr << "pinmask: warning: " << w << "\n";
    const WorkingDistance wd = compute_working_distance(camera, geometry, wo);
    std::vector<CameraInput> inputs = camera_inputs(o.camera, camera);
    if (!solved.empty()) inputs[0].source = "solved for N px per cell at u";
    if (!o.save_camera.empty()) io::write_camera_file(o.save_camera, camera);
    if (o.json) {
        auto j = design_json(r, wd);
        j["kernel_warnings"] = validity.warnings;
        for (const CameraInput& in : inputs) j["input_sources"][in.symbol] = in.source;
        std::cout << io::json_strict::pretty(j) << "\n";
    } else {
        std::cout << design_table(r, wd, solved, inputs);
        if (!o.save_camera.empty()) std::cerr << "wrote " << o.save_camera << "\n";
    }
}

constexpr const char* kFooter =
    "Design values are for a distant object (u = inf), as the paper quotes them; the \"at u\" "
    "rows use --object-distance (a point source at u: 1/z_eff = 1/f - 1/f' + 1/u), and the "
    "kernel models use those. --json prints one object with unit-suffixed keys (_m = metres, "
    "_px = pixels); infinite values are null, with the reason under \"notes\".\n"
    "Examples:\n"
    "  pinmask design --preset paper\n"
    "  pinmask design --lens-focal 55mm --object-distance inf --json   (f = f': Fraunhofer)\n"
    "  pinmask design --pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm \\\n"
    "      --sensor-distance 20mm --object-distance 2m --wavelength 530nm --pixels-per-cell 21\n"
    "      (solves d = 345 um for 21 whole pixels per cell at 2 m)";

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
    cmd->add_flag("--json", o->json, "Print the report as one JSON object on stdout");
    cmd->callback([o] { run(*o); });
}

}  // namespace

void add_design(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
