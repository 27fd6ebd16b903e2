// `pinmask psf`: mask file -> PSF of one period (float32 TIFF, optionally .npy) plus a JSON
// sidecar, written together (io/psf_files.hpp). The PSF is design/psf/psf's synthesis: the mask's
// kernel placed at every pinhole's cell on the (n ppc)^2 torus, sum 1.
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "cli/commands.hpp"
#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/kernel_validity.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "design/psf/psf_settings.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"

namespace pinmask::cli {
namespace {

struct PsfCommandOptions {
    std::string mask;
    std::string output;
    bool npy = false;
    std::string kernel;  // empty: the mask's model
    std::string kernel_path;
    double energy_fraction = KernelOptions{}.energy_fraction;
    std::string geometry = "integer";
    std::optional<std::string> object_distance;  // exact: default the mask's u
    std::optional<std::string> size;             // exact: ROWSxCOLS, default the sensor
    bool json = false;
};

// The exact-geometry PSF for these options (design/psf/psf_exact), with the distance used.
Plane exact_for(const PsfCommandOptions& o, const Mask& mask, const KernelOptions& ko, double& u) {
    ExactPsfOptions eo;
    eo.kernel = ko;
    u = o.object_distance
            ? parse_length_m(*o.object_distance, "--object-distance", AllowInfinity::kYes)
            : mask.camera.object_distance_m;
    check_object_distance(mask.camera, u, "--object-distance");
    eo.object_distance_m = u;
    if (o.size) {
        const Size2 rc = parse_size(*o.size, "--size");  // typed ROWSxCOLS: first number = rows
        eo.rows = rc.cols;
        eo.cols = rc.rows;
    }
    return exact_psf(mask, eo);
}

void run(const PsfCommandOptions& o) {
    if (!(o.energy_fraction > 0.0 && o.energy_fraction <= 1.0)) {
        throw invalid_field(
            "--energy", std::to_string(o.energy_fraction),
            "must be in (0, 1]: the fraction of the kernel's energy its support keeps");
    }
    if (!o.kernel.empty()) parse_kernel_model(o.kernel, "--kernel");
    check_kernel_settings(o.kernel, o.kernel_path);
    {
        const std::string ext = std::filesystem::path(o.output).extension().string();
        if (ext != ".tif" && ext != ".tiff") {
            throw invalid_field("-o", o.output, "must end in .tif or .tiff");
        }
    }
    {
        std::filesystem::path npy = o.output;
        plan_outputs({{"mask", o.mask}, {"--kernel-path", o.kernel_path}},
                     {{"-o", o.output},
                      {"-o (npy)", o.npy ? npy.replace_extension(".npy") : ""},
                      {"-o (sidecar)", io::psf_sidecar_path(o.output)}});
    }
    Mask mask = io::read_mask_file(o.mask);
    if (!o.kernel.empty()) {
        mask.psf.kernel.model = o.kernel;
        mask.psf.kernel.measured_path = o.kernel_path;
    }
    KernelOptions ko;
    ko.energy_fraction = o.energy_fraction;
    const int ppc = mask.psf.pixels_per_cell;
    const bool exact = o.geometry == "exact";
    if (!exact && (o.object_distance || o.size)) {
        throw invalid_field(o.size ? "--size" : "--object-distance",
                            o.size ? *o.size : *o.object_distance,
                            "only used with --geometry exact (the integer model is one period "
                            "at the mask's pixels per cell)");
    }
    double u = mask.camera.object_distance_m;
    if (!exact) check_psf_memory(mask.pattern.n, ppc, 2, 0);  // the PSF and its float copy
    const Kernel kernel = mask_kernel(mask, ko);
    const Plane psf = exact ? exact_for(o, mask, ko, u) : synthesize_psf(mask.pattern, kernel, ppc);
    KernelValidity validity = kernel_validity(mask.camera, kernel.model, kernel.enclosed_energy);
    for (auto& w : validity.warnings) w = spell_flags(w);
    for (const auto& w : validity.warnings) std::cerr << "pinmask: warning: " << w << "\n";

    io::PsfSidecar s = io::psf_sidecar_for(mask, kernel, o.mask);
    if (exact) s.geometry = "full-frame";  // a linear PSF of the sensor, not one period
    const auto written = io::write_psf_files(o.output, psf, s, o.npy);

    s.rows = static_cast<int>(psf.rows());
    s.cols = static_cast<int>(psf.cols());
    if (o.json) {
        nlohmann::ordered_json j = io::psf_sidecar_to_json(s);
        nlohmann::ordered_json paths = nlohmann::ordered_json::array();
        for (const auto& p : written) paths.push_back(p.string());
        j["written"] = paths;
        j["warnings"] = validity.warnings;
        j["geometry"] = o.geometry;
        if (exact)
            j["object_distance_m"] =
                std::isinf(u) ? nlohmann::ordered_json("inf") : nlohmann::ordered_json(u);
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::ostringstream out;
    for (const auto& p : written) out << "wrote " << p.string() << "\n";
    if (exact) {
        out << "  PSF            " << psf.rows() << " x " << psf.cols()
            << " px, exact geometry at u = " << format_length(u) << " (spots at their Eq. (3) "
            << "positions, the whole tiled mask), sum " << psf.sum() << "\n";
    } else {
        out << "  PSF            " << psf.rows() << " x " << psf.cols() << " px (grid " << s.grid_n
            << " x " << ppc << " px per cell), sum 1\n";
    }
    out << "  kernel         " << s.kernel_model << " ("
        << (validity.model_accurate ? kernel.model_reason : "NOT accurate: see the warning")
        << "), support " << s.kernel_rows << " x " << s.kernel_cols << " px, "
        << "enclosed energy " << kernel.enclosed_energy
        << (kernel.support_capped ? " (support capped at the period)" : "") << "\n";
    out << "  wavelengths   ";
    for (const auto& [lambda, w] : kernel.wavelengths) {
        out << " " << format_length(lambda) << " (weight " << w << ")";
    }
    out << "\n  geometry hash  " << s.mask_geometry_hash << "\n";
    std::cout << out.str();
}

constexpr const char* kFooter =
    "Writes OUT.tiff (32-bit float), with --npy also OUT.npy (float32, row-major), and the "
    "sidecar OUT.json (format pinmask-psf, version 1: mask geometry hash, pixel pitch, pixels "
    "per cell, resolved kernel model and wavelengths, normalisation sum=1, size). All files "
    "appear together or not at all.\n"
    "Kernel support: grown until --energy of the continuous 1-D energy per axis is kept, at most "
    "one period (n x pixels per cell); the cut tail is dropped and the kernel renormalised (the "
    "sidecar records the kept energy). paper-fig3b is the paper's measured 8 x 8 table (Fig. 3b), "
    "defined for 8 pixels per cell only.\n"
    "Geometry: integer (default) is the decoder's model, one period on the (n ppc)^2 torus; exact "
    "is what the sensor records from a point at --object-distance (default the mask's u): every "
    "pinhole of the tiled mask at its true sub-pixel position, pitch d (1 - f/f' + f/u) / w, "
    "box spots of side d |1 - f/f' + f/u| / w integrated over the pixels at their own centres, "
    "other kernels moved there by area resampling, over the sensor or --size ROWSxCOLS.\n"
    "Example: pinmask psf m.mask.json -o psf.tiff --npy\n"
    "         pinmask psf m.mask.json -o exact.tiff --geometry exact --object-distance 2m";

void setup(CLI::App& app) {
    auto o = std::make_shared<PsfCommandOptions>();
    auto* cmd = app.add_subcommand(
        "psf",
        "Synthesise the PSF of one period of a mask and write it as TIFF (+ .npy) with a "
        "JSON sidecar.");
    cmd->footer(kFooter);
    cmd->add_option("mask", o->mask, "Mask file (*.mask.json)")->required();
    cmd->add_option("-o,--output", o->output, "Output PSF image, .tif or .tiff")->required();
    cmd->add_flag("--npy", o->npy, "Also write the PSF as float32 .npy next to the TIFF");
    cmd->add_option(
        "--kernel", o->kernel,
        "Override the mask's kernel model: " + kernel_model_names() + " (default: the mask's)");
    cmd->add_option("--kernel-path", o->kernel_path, "Kernel image for --kernel measured");
    cmd->add_option("--energy", o->energy_fraction,
                    "Fraction of the continuous 1-D kernel energy the support must keep per "
                    "axis, in (0, 1]")
        ->capture_default_str();
    cmd->add_option("--geometry", o->geometry,
                    "integer (the decoder's cyclic model) | exact (spots at their true positions "
                    "for --object-distance, over the sensor or --size)")
        ->check(CLI::IsMember({"integer", "exact"}))
        ->capture_default_str();
    cmd->add_option("--object-distance", o->object_distance,
                    "Exact geometry: object distance u (e.g. 6m, inf; default the mask's)");
    cmd->add_option("--size", o->size,
                    "Exact geometry: window ROWSxCOLS in pixels, centred on the axis (default the "
                    "sensor)");
    cmd->add_flag("--json", o->json,
                  "Print the sidecar plus the written paths as JSON on stdout instead of the "
                  "summary");
    cmd->callback([o] { run(*o); });
}

}  // namespace

void add_psf(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
