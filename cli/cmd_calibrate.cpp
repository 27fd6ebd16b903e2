// `pinmask calibrate`: a point-source capture through the whole mask -> measured geometry,
// per-pinhole record, kernel and calibrated PSF. Parses the flags, reads the inputs, runs the
// transaction decode/calibrate/calibrate_run and writes io/calibrate_json's files into a new
// folder, together or not at all; prints a summary or the JSON.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.hpp"
#include "cli/options/calibrate_inputs.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/outputs/progress.hpp"
#include "core/errors/error.hpp"
#include "core/image/raw_io.hpp"
#include "decode/calibrate/calibrate_run.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/calibrate_json.hpp"
#include "io/mask_json.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

struct CalibrateCommandOptions {
    std::string capture, mask, dark, output;
    CameraOptions camera;
    calibrate::CalibrationOptions cal;
    std::string saturation = "auto";
    std::string bayer = "sum2x2";
    bool json = false;
};

void run(CalibrateCommandOptions& o) {
    const fs::path dir = o.output;
    if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir)))
        throw invalid_field("-o", o.output,
                            "must be a new or empty folder (nothing is overwritten)");
    if (!dir.parent_path().empty() && !fs::is_directory(dir.parent_path()))
        throw invalid_field("-o", o.output, "its parent folder does not exist");
    apply_saturation_flag(o.saturation, o.cal);
    calibrate::validate(o.cal);
    const BayerMode bayer = parse_bayer_mode(o.bayer);
    CalibrateRequest q;
    q.mask = io::read_mask_file(o.mask);
    o.camera.base = q.mask.camera;
    q.mask.camera = resolve_camera(o.camera);
    double full_scale = 1.0;
    RawInfo raw, raw_dark;
    q.capture = read_grey(o.capture, "capture", bayer, &full_scale, raw);
    o.cal.pixel_binning = raw.binning;  // a Bayer RAW read as 2 x 2 blocks
    // Integer files saturate at their largest count; float files have no known ceiling.
    if (o.saturation == "auto" && full_scale > 1.0) o.cal.saturation_level = full_scale;
    if (!o.dark.empty()) q.dark = read_grey(o.dark, "dark frame", bayer, nullptr, raw_dark);
    std::cerr << "calibrate: registering " << q.capture.cols() << " x " << q.capture.rows()
              << " px against " << q.mask.pattern.pinholes.size() << " pinholes x "
              << q.mask.pattern.tiles_rows * q.mask.pattern.tiles_cols << " tiles\n";
    // Progress: each phase, and the fit's iterations (a large frame fits for tens of seconds).
    ProgressLine bar("pinmask calibrate");
    o.cal.progress = [&](const std::string& phase, int it, int cap) {
        if (it == 0) {
            bar.phase(phase);
            return;
        }
        // The fit runs a few rounds of at most `cap` iterations: the bar shows the share of
        // two rounds' caps, the text the count.
        bar.update(std::min(0.99, double(it) / (2.0 * cap)),
                   phase + ": " + std::to_string(it) + " iterations");
    };
    q.capture_name = o.capture;
    q.options = o.cal;
    q.kernel_file = (dir / "kernel.tiff").string();
    q.spell = [](const std::string& w) { return spell_flags(w); };
    const CalibrateReport report = run_calibrate_request(std::move(q));
    bar.finish();
    const calibrate::CalibrationSummary& s = report.summary;
    for (const std::string& w : s.warnings)
        std::cerr << "pinmask: warning: " << spell_flags(w) << "\n";
    const Json config = {{"capture", o.capture},
                         {"mask", o.mask},
                         {"dark", o.dark},
                         {"output", o.output},
                         {"max_rotation_deg", o.cal.max_rotation_deg},
                         {"pitch_range", o.cal.pitch_range},
                         {"threshold_sigmas", o.cal.threshold_sigmas},
                         {"saturation", o.saturation}};
    io::write_calibration_files(report, dir, config, o.mask, "pinmask calibrate " + o.capture);
    if (o.json) {
        std::cout << io::calibration_result_json(s, dir).dump(2) << "\n";
        return;
    }
    std::cout << "calibrate " << o.capture << " -> " << o.output << "/\n"
              << "  rotation   " << s.rotation_deg << " +- " << s.rotation_sigma_deg
              << " deg (counter-clockwise on screen, rows down)\n"
              << "  pitch      x " << s.pitch_x_px << " +- " << s.pitch_x_sigma_px << ", y "
              << s.pitch_y_px << " +- " << s.pitch_y_sigma_px << " px (design " << s.design_pitch_px
              << ")\n"
              << "  position   x " << s.position_x_px << ", y " << s.position_y_px
              << " px (pattern cell (0, 0) of tile " << s.first_tile.row << "," << s.first_tile.col
              << ")\n"
              << "  pinhole    side " << s.fit.side_m * 1e6 << " um (x " << s.fit.side_scale
              << " +- " << s.fit.side_scale_sigma << " of the design), "
              << kernel_model_name(s.fit.family) << " kernel\n"
              << "  pinholes   " << s.fit.pinholes.size() << " fitted, " << s.missing.size()
              << " missing, " << s.extra_spots.size() << " extra spots\n"
              << "  leak       " << s.background << " +- " << s.background_sigma
              << " counts/px (optical density " << (s.optical_density_is_bound ? "> " : "")
              << s.optical_density << (s.optical_density_is_bound ? "" : " +- ")
              << (s.optical_density_is_bound ? "" : std::to_string(s.optical_density_sigma))
              << "), dark level " << s.dark_level << " (" << s.dark_source << ")\n"
              << "  band       " << s.band << "\n"
              << "  fit        chi2/dof " << s.fit.chi2_reduced << ", " << s.fit.iterations
              << " iterations\n"
              << "  period PSF " << s.psfs.period_reason << "\n"
              << "  wrote      psf.tiff (+ psf.json)" << (s.psfs.period ? ", psf-period.tiff" : "")
              << ", kernel.tiff, calibrated.mask.json, report.pdf, calibration.json\n";
}

constexpr const char* kFooter =
    "Input: a capture of a point source (laser pinhole, distant LED) through the whole mask: "
    "several periods, every pinhole's spot. RAW files are read as sensor data (see decode). "
    "The forward model (every pinhole's kernel at its lattice site, one gain per pinhole, the "
    "pinhole side, leak and background) is fitted to the whole capture; standard errors come from "
    "the Fisher information. Pitch and position are in capture pixels; rotation in degrees, "
    "positive counter-clockwise on screen with rows running down (scipy.ndimage.rotate's sense): "
    "turn the mask holder clockwise by the reported angle to undo it. A pinhole is missing when "
    "its gain + 3.72 sigma is below half the median (false alarm 1e-4 per pinhole). Refused "
    "(exit 2, nothing written) when the fit cannot be trusted: too few photons, a capture the "
    "model does not explain, a rotation beyond --max-rotation.\n"
    "Writes DIR/psf.tiff (+ psf.json sidecar): the full-frame calibrated PSF (the measured "
    "kernel at every measured spot), which `pinmask decode CAPTURE --psf DIR/psf.tiff` uses "
    "directly; DIR/psf-period.tiff: the one-period cyclic PSF when the measured lattice fits a "
    "whole-pixel torus; DIR/kernel.tiff; DIR/calibrated.mask.json (kernel measured, geometry in "
    "provenance.scores); DIR/report.pdf; DIR/calibration.json (configuration and results).\n"
    "Example: pinmask calibrate point.tiff --mask m.mask.json --dark dark.tiff -o cal --json";

void setup(CLI::App& app) {
    auto o = std::make_shared<CalibrateCommandOptions>();
    auto* cmd = app.add_subcommand(
        "calibrate",
        "Fit the design's forward model to a point-source capture: rotation, pitch, position, "
        "pinhole side, per-pinhole gains (missing pinholes), leak, with standard errors; write "
        "the calibrated PSF, mask and a report.");
    cmd->footer(kFooter);
    cmd->add_option("point", o->capture, "Point-source capture (TIFF, PNG, npy, camera RAW)")
        ->required();
    cmd->add_option("--mask", o->mask, "The mask's design (*.mask.json)")->required();
    cmd->add_option("--dark", o->dark, "Dark frame (same size), subtracted first");
    cmd->add_option("-o,--output", o->output, "Output folder (new or empty)")->required();
    cmd->add_option("--max-rotation", o->cal.max_rotation_deg,
                    "Rotations searched: +- this many degrees (counter-clockwise on screen "
                    "positive); a capture rotated further is refused")
        ->capture_default_str();
    cmd->add_option("--pitch-range", o->cal.pitch_range,
                    "Spot pitches searched: the design's pixels per cell +- this fraction")
        ->capture_default_str();
    cmd->add_option("--threshold", o->cal.threshold_sigmas,
                    "Spot detection threshold, noise sigmas above the background")
        ->capture_default_str();
    cmd->add_option("--saturation", o->saturation,
                    "Saturation level, counts: auto (an integer file's largest count; for a "
                    "float file a flat top at its largest value, with a warning) | none | VALUE")
        ->capture_default_str();
    cmd->add_option("--bayer", o->bayer,
                    "Camera RAW: sum2x2 (half-resolution grey) | green (alias g) | r | b")
        ->capture_default_str();
    add_camera_options(*cmd, o->camera);
    cmd->add_flag("--json", o->json, "Print the results as JSON on stdout");
    cmd->callback([o, cmd] {
        if (cmd->count("--preset") > 0)
            throw invalid_field("--preset", o->camera.preset,
                                "calibrate uses the mask's camera; override single parameters");
        run(*o);
    });
}

}  // namespace

void add_calibrate(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
