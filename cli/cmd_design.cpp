// `pinmask design`: the optics report (DESIGN.md section 1) for a preset or explicit parameters,
// as a table (quantity, value, note) or, with --json, one JSON object whose keys carry units.
// Infinite values (z_eff at f = f', the pinhole for integer pixels when M = 0, u = inf) are
// written as JSON null with the reason under "notes" (key -> text).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/camera_options.hpp"
#include "cli/command.hpp"
#include "io/json_strict.hpp"
#include "core/error.hpp"
#include "core/units.hpp"
#include "design/kernel_validity.hpp"
#include "design/optics.hpp"

namespace pinmask::cli {
namespace {

struct DesignOptions {
    CameraOptions camera;
    GeometryOptions geometry;
    std::string kernel = "auto";
    double lsi_tolerance_px = 1.0;
    bool json = false;
};

std::string num(double v, int digits = 4) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string length(double v) { return format_length(v); }

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
        throw invalid_field("--spacing", num(g.spacing), "must be finite and >= 0");
    }
    return {g.grid, g.holes, g.tiles, g.tiles};
}

// A number, or null with a note when it is infinite.
void put(nlohmann::ordered_json& j, nlohmann::ordered_json& notes, const std::string& key, double v,
         const std::string& why_infinite = "") {
    if (std::isfinite(v)) {
        j[key] = v;
    } else {
        j[key] = nullptr;
        notes[key] = std::string(v > 0 ? "+inf" : "-inf") +
                     (why_infinite.empty() ? "" : ": " + why_infinite);
    }
}

nlohmann::ordered_json to_json(const OpticsReport& r) {
    using Json = nlohmann::ordered_json;
    Json j, notes = Json::object();
    const Camera& c = r.camera;
    Json cam;
    put(cam, notes, "object_distance_m", c.object_distance_m, "distant object");
    put(cam, notes, "lens_focal_m", c.lens_focal_m, "no lens");
    cam["sensor_distance_m"] = c.sensor_distance_m;
    cam["wavelength_m"] = c.wavelength_m;
    cam["pixel_pitch_m"] = c.pixel_pitch_m;
    cam["pinhole_m"] = c.pinhole_m;
    cam["sensor_px"] = {c.sensor_cols, c.sensor_rows};
    j["camera"] = cam;
    j["geometry"] = {{"n", r.geometry.n},
                     {"holes", r.geometry.holes},
                     {"tiles", {r.geometry.tiles_rows, r.geometry.tiles_cols}}};
    const std::string focus = "f = f' (Fraunhofer limit: 1/z_eff = 0)";
    j["optimum_pinhole_m"] = r.optimum_pinhole_m;
    j["fresnel_number"] = r.fresnel_number;
    j["fresnel_number_with_lens"] = r.fresnel_number_with_lens;
    j["fresnel_number_with_lens_at_u"] = r.fresnel_number_with_lens_at_u;
    put(j, notes, "effective_distance_m", r.effective_distance_m, focus);
    put(j, notes, "effective_distance_at_u_m", r.effective_distance_at_u_m, "1/f - 1/f' + 1/u = 0");
    j["magnification"] = r.magnification;
    j["magnification_at_u"] = r.magnification_at_u;
    j["geometric_spot_m"] = r.geometric_spot_m;
    j["geometric_spot_at_u_m"] = r.geometric_spot_at_u_m;
    j["pixels_per_cell"] = r.pixels_per_cell;
    j["pixels_per_cell_at_u"] = r.pixels_per_cell_at_u;
    j["integer_pixels_per_cell"] = r.integer_pixels_per_cell;
    put(j, notes, "pinhole_for_integer_pixels_m", r.pinhole_for_integer_pixels_m,
        "magnification 1 - f/f' = 0: every pinhole images to the same spot");
    j["max_separation_m"] = r.max_separation_m;
    j["lsi_tolerance_px"] = r.options.lsi_tolerance_px;
    j["lsi_min_object_distance_m"] = r.lsi_min_object_distance_m;
    j["lsi_mismatch_px"] = r.lsi_mismatch_px;
    j["lsi_shift_invariant"] = r.is_shift_invariant();
    j["psf_size_px"] = r.psf_size_px;
    j["periods_on_sensor"] = {{"cols", r.periods_on_sensor_cols},
                              {"rows", r.periods_on_sensor_rows}};
    j["mask_size_m"] = {{"width", r.mask_width_m}, {"height", r.mask_height_m}};
    j["open_fraction"] = r.open_fraction;
    j["light_gain"] = r.light_gain;
    j["kernel_model"] = kernel_model_name(r.kernel_model);
    j["kernel_reason"] = r.kernel_reason;
    j["notes"] = notes;
    return j;
}

std::string table(const OpticsReport& r) {
    const Camera& c = r.camera;
    const std::string at_u = "u = " + length(c.object_distance_m);
    std::vector<std::vector<std::string>> rows = {
        {"magnification M", num(r.magnification), "1 - f/f' (u = inf; < 0 past focus)"},
        {"  at u", num(r.magnification_at_u), "1 - f/f' + f/u, " + at_u},
        {"geometric spot = cell pitch p", length(r.geometric_spot_m),
         "d |M| (u = inf, as the paper quotes)"},
        {"  at u", length(r.geometric_spot_at_u_m), at_u},
        {"pixels per cell", num(r.pixels_per_cell), "p / w"},
        {"  at u", num(r.pixels_per_cell_at_u), at_u},
        {"integer pixels per cell n_px", std::to_string(r.integer_pixels_per_cell),
         "nearest integer (u = inf), at least 1"},
        {"pinhole for n_px pixels per cell", length(r.pinhole_for_integer_pixels_m),
         "n_px w / |1 - f/f'|"},
        {"optimum single pinhole", length(r.optimum_pinhole_m), "1.56 sqrt(lambda f)"},
        {"Fresnel number, no lens", num(r.fresnel_number), "d^2 / (4 lambda f)"},
        {"effective distance z_eff", length(r.effective_distance_m),
         "f f' / (f' - f), u = inf (inf: f = f'; < 0: past focus)"},
        {"  at u", length(r.effective_distance_at_u_m), "1/z = 1/f - 1/f' + 1/u"},
        {"Fresnel number with lens", num(r.fresnel_number_with_lens),
         "d^2 / (4 lambda |z_eff|), u = inf"},
        {"  at u", num(r.fresnel_number_with_lens_at_u), "used by the kernel models"},
        {"largest separation s_max", length(r.max_separation_m), "n d"},
        {"LSI min object distance", length(r.lsi_min_object_distance_m),
         "f s_max / (" + num(r.options.lsi_tolerance_px) + " px * w)"},
        {"LSI mismatch at u", num(r.lsi_mismatch_px) + " px",
         std::string("f s_max / (u w): ") +
             (r.is_shift_invariant() ? "shift invariant" : "NOT shift invariant") + " within " +
             num(r.options.lsi_tolerance_px) + " px"},
        {"PSF size (one period)",
         std::to_string(r.psf_size_px) + " x " + std::to_string(r.psf_size_px) + " px", "n n_px"},
        {"periods on the sensor",
         num(r.periods_on_sensor_cols, 3) + " x " + num(r.periods_on_sensor_rows, 3),
         std::to_string(c.sensor_cols) + " x " + std::to_string(c.sensor_rows) + " px / PSF size"},
        {"mask size", length(r.mask_width_m) + " x " + length(r.mask_height_m),
         "n tiles d per side"},
        {"open fraction", num(100 * r.open_fraction, 3) + " %", "K / n^2"},
        {"light gain", num(r.light_gain) + " x", "K: light over one pinhole"},
        {"kernel model", kernel_model_name(r.kernel_model), r.kernel_reason},
    };
    std::size_t w0 = 8, w1 = 5;
    for (const auto& row : rows) {
        w0 = std::max(w0, row[0].size());
        w1 = std::max(w1, row[1].size());
    }
    std::ostringstream s;
    auto line = [&](const std::string& a, const std::string& b, const std::string& n) {
        s << a << std::string(w0 + 2 - a.size(), ' ') << b << std::string(w1 + 2 - b.size(), ' ')
          << n << "\n";
    };
    line("quantity", "value", "note");
    for (const auto& row : rows) line(row[0], row[1], row[2]);
    return s.str();
}

void run(const DesignOptions& o) {
    const Camera camera = resolve_camera(o.camera);
    const PatternGeometry geometry = resolve_geometry(o.geometry);
    const KernelModel kernel = parse_kernel_model(o.kernel, "--kernel");
    if (!(o.lsi_tolerance_px > 0) || !std::isfinite(o.lsi_tolerance_px)) {
        throw invalid_field("--lsi-tolerance", num(o.lsi_tolerance_px), "must be finite and > 0");
    }
    OpticsReport r = compute_optics(camera, geometry, kernel, {o.lsi_tolerance_px});
    const KernelValidity validity = kernel_validity(camera, r.kernel_model);  // never "accurate"
    if (!validity.model_accurate) r.kernel_reason = "NOT accurate: " + validity.warnings.front();
    for (const auto& w : validity.warnings) std::cerr << "pinmask: warning: " << w << "\n";
    if (o.json) {
        auto j = to_json(r);
        j["kernel_warnings"] = validity.warnings;
        std::cout << io::json_strict::pretty(j) << "\n";
    } else {
        std::cout << table(r);
    }
}

constexpr const char* kFooter =
    "Design values are for a distant object (u = inf), as the paper quotes them; the \"at u\" "
    "rows use --object-distance (a point source at u: 1/z_eff = 1/f - 1/f' + 1/u), and the "
    "kernel models use those. --json prints one object with unit-suffixed keys (_m = metres, "
    "_px = pixels); infinite values are null, with the reason under \"notes\".\n"
    "Examples:\n"
    "  pinmask design --preset paper\n"
    "  pinmask design --lens-focal 55mm --object-distance inf --json   (f = f': Fraunhofer)";

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
                    "Kernel model to report: auto (chosen from the Fresnel number with the lens "
                    "at u) | box | fraunhofer | fresnel | paper-fig3b | measured")
        ->capture_default_str();
    cmd->add_option("--lsi-tolerance", o->lsi_tolerance_px,
                    "Shift-invariance tolerance in pixels: the object term f s_max / u may reach "
                    "this")
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "Print the report as one JSON object on stdout");
    cmd->callback([o] { run(*o); });
}

const Registration kDesign(10, "design", setup);

}  // namespace
}  // namespace pinmask::cli
