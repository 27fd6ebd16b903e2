// `pinmask simulate`: mask + scene -> a simulated capture
// (optimize/simulate/simulate_pipeline.hpp), optionally the whole sensor and a matching dark frame,
// with the resolved configuration (io/simulate_json) written next to the capture as
// OUT.config.json. All files are staged and appear together or not at all.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/command_footers.hpp"
#include "cli/commands.hpp"
#include "cli/options/flag_names.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/outputs/image_output.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "io/mask_json.hpp"
#include "io/simulate_json.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate_pipeline.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

struct SimulateOptions {
    std::string mask;
    std::string scene = "letter-R";
    std::string snr = "30";
    std::optional<double> photons;
    SensorFlags sensor_flags;
    bool full_sensor = false;
    std::optional<std::string> sensor;
    std::string geometry = "integer";            // exact: design/psf/psf_exact over the sensor
    std::optional<std::string> object_distance;  // exact: u, default the mask's
    std::optional<std::string> size;             // exact: ROWSxCOLS window, default the sensor
    std::uint64_t seed = 1;
    std::string dark_frame;
    std::string output;
    bool allow_violations = false;
    bool json = false;
    bool explain = false;
    int threads = 0;  // FFTW threads for >= 512 x 512 transforms; 0: all cores
    std::string precision = "auto";
};

void run(const SimulateOptions& o, const CLI::App& cmd) {
    if (o.threads > 0) set_fft_threads(o.threads);
    // Everything checkable before any work.
    check_image_extension(o.output, "-o");
    if (!o.dark_frame.empty()) check_image_extension(o.dark_frame, "--dark-frame");
    if (!o.dark_frame.empty() && fs::path(o.dark_frame) == fs::path(o.output)) {
        throw invalid_field("--dark-frame", o.dark_frame, "must differ from -o");
    }
    plan_outputs({{"mask", o.mask}, {"--scene", fs::exists(o.scene) ? o.scene : ""}},
                 {{"-o", o.output},
                  {"--dark-frame", o.dark_frame},
                  {"-o (config)", o.output + ".config.json"}});
    SimulatePipelineOptions po;
    SimulationOptions& sim = po.sim;
    sim.noise = one_noise_model(o.snr, o.photons, o.sensor_flags, cmd, po.noise_notes);
    po.photon_stages = {o.sensor_flags.optical_density.has_value(),
                        o.sensor_flags.dark_current.has_value(),
                        o.sensor_flags.read_noise.has_value(), o.sensor_flags.full_well.has_value(),
                        o.sensor_flags.bits.has_value()};
    sim.seed = o.seed;
    sim.precision = parse_precision(o.precision, "--precision");
    sim.dark_frame = !o.dark_frame.empty();
    if (sim.dark_frame && sim.noise.kind != NoiseKind::kPhoton) {
        throw invalid_field("--dark-frame", o.dark_frame,
                            "needs the photon model (--photons N): the --snr model has no leak, "
                            "dark current or read noise to record");
    }
    po.scene = scene_from_name(o.scene);
    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    const Mask mask = io::read_mask_file(o.mask, ro);
    sim.full_sensor = o.full_sensor;
    // The pipeline refuses what does not go together (--sensor without --full-sensor, a
    // distance or window without --geometry exact) and a distance the camera cannot focus.
    if (o.sensor) po.sensor = parse_size(*o.sensor, "--sensor");
    po.exact_geometry = o.geometry == "exact";
    if (o.object_distance)
        po.object_distance_m =
            parse_length_m(*o.object_distance, "--object-distance", AllowInfinity::kYes);
    if (o.size) po.window = parse_size(*o.size, "--size");  // typed ROWSxCOLS
    const SimulatePipelineResult r = run_simulate_pipeline(mask, po);
    const SimulatedCapture& s = r.capture;
    const int m = r.summary.period_px;
    std::vector<std::string> explain;  // the library's lines, fields spelled as flags
    for (const std::string& line : r.summary.explain) explain.push_back(spell_flags(line));
    if (o.full_sensor && !s.whole_period_on_sensor) {
        std::cerr << "pinmask simulate: warning: the sensor is smaller than one " << m << " x " << m
                  << " period: no full period to decode\n";
    }
    warn_png_clipping("pinmask simulate", o.output, s.capture);
    warn_all_zero("pinmask simulate", "the capture", s.capture,
                  "no light counted, or every pixel saturated: check --photons and --full-well");
    if (!o.dark_frame.empty()) warn_png_clipping("pinmask simulate", o.dark_frame, s.dark);
    const std::string config_path = o.output + ".config.json";
    io::SimulateConfigInputs ci{o.mask, o.output, o.dark_frame, o.geometry, o.full_sensor, o.seed};
    const ordered_json config = io::simulate_config_json(ci, mask, po, r, explain);

    StagedFiles files;
    files.stage(o.output, [&](const fs::path& tmp) { write_image_as(tmp, o.output, s.capture); });
    if (!o.dark_frame.empty()) {
        files.stage(o.dark_frame,
                    [&](const fs::path& tmp) { write_image_as(tmp, o.dark_frame, s.dark); });
    }
    files.stage_bytes(config_path, config.dump(2) + "\n");
    files.commit();
    if (o.explain) {
        for (const std::string& line : explain) std::cerr << "simulate: " << line << "\n";
    }
    if (o.json) {
        std::cout << io::simulate_summary_json(ci, r, po.sim.noise).dump() << "\n";
        return;
    }
    std::cout << "wrote " << o.output << " (" << s.capture.cols() << " x " << s.capture.rows()
              << ", " << s.capture.n_channels() << " channel(s))\n";
    if (!o.dark_frame.empty()) std::cout << "wrote " << o.dark_frame << " (dark frame)\n";
    std::cout << "wrote " << config_path << "\n";
}

void setup(CLI::App& app) {
    auto o = std::make_shared<SimulateOptions>();
    auto* cmd = app.add_subcommand(
        "simulate",
        "Simulate a capture of a scene through a mask: one period (or the whole sensor), with "
        "Gaussian SNR noise or a photon/sensor noise model, seeded and deterministic.");
    cmd->footer(kSimulateFooter);
    cmd->add_option("mask", o->mask, "Mask file (*.mask.json); its PSF is synthesised")->required();
    cmd->add_option("--scene", o->scene,
                    "letter-R | usaf | siemens-star | checker | point | natural (seed 0) | an "
                    "image FILE (PNG/TIFF/npy, grey or RGB, values in [0, 1] after normalising "
                    "by the file's full scale, resampled to one period)")
        ->capture_default_str();
    auto* snr = cmd->add_option("--snr", o->snr,
                                "Gaussian noise at this SNR in dB, 10 log10(mean(c^2) / sigma^2) "
                                "over the noiseless capture c; 'inf' = noiseless")
                    ->capture_default_str();
    auto* photons = cmd->add_option(
        "--photons", o->photons,
        "Photon model: mean photo-electrons per pixel through ONE pinhole for a uniform scene "
        "of value 1 (K pinholes give K times that); Poisson shot noise");
    photons->excludes(snr);
    add_sensor_flags(*cmd, o->sensor_flags);
    cmd->add_flag("--full-sensor", o->full_sensor,
                  "Tile the period over the whole sensor (the mask's camera sensor size, or "
                  "--sensor)");
    cmd->add_option("--sensor", o->sensor,
                    "With --full-sensor: sensor size WIDTHxHEIGHT in pixels (default: the "
                    "mask's camera)");
    cmd->add_option("--geometry", o->geometry,
                    "integer (the cyclic model, one period or tiled) | exact (every pinhole at "
                    "its true position for --object-distance, linear convolution over the sensor "
                    "or --size ROWSxCOLS)")
        ->check(CLI::IsMember({"integer", "exact"}))
        ->capture_default_str();
    cmd->add_option("--object-distance", o->object_distance,
                    "Exact geometry: object distance u (e.g. 2m, inf; default the mask's)");
    cmd->add_option("--size", o->size,
                    "Exact geometry: sensor window ROWSxCOLS (default the sensor)");
    cmd->add_option("--seed", o->seed, "Seed of the noise (the dark frame has its own stream)")
        ->capture_default_str();
    cmd->add_option("--dark-frame", o->dark_frame,
                    "Also write the matching dark frame (all-opaque film: leak + dark current + "
                    "read noise, same exposure); photon model only");
    cmd->add_option("-o,--output", o->output, "Capture file: .tif/.tiff, .png or .npy")->required();
    cmd->add_option("--threads", o->threads,
                    "FFTW threads for transforms of >= 512 x 512 (0: all cores); the bytes do "
                    "not depend on it with PINMASK_WISDOM=off (the wisdom cache plans per count: "
                    "float32 may differ in the last bits)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    cmd->add_option("--precision", o->precision,
                    "auto (float32 from a 256 x 256 convolution grid) | single | double: the "
                    "convolution's precision (noise is always drawn in double)")
        ->check(CLI::IsMember(name_list(kPrecisionNames)))
        ->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Read a mask whose pinholes break its spacing rule");
    cmd->add_flag("--json", o->json, "Print a JSON summary on stdout");
    cmd->add_flag("--explain", o->explain,
                  "List on stderr what was run and what was skipped, and why");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_simulate(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
