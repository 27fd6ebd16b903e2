// `pinmask simulate`: mask + scene -> a simulated capture (optimize/simulate.hpp), optionally the
// whole sensor and a matching dark frame, with the resolved configuration written next to the
// capture as OUT.config.json. All files are staged and appear together or not at all.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/noise_options.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/image_io.hpp"
#include "core/output_set.hpp"
#include "core/units.hpp"
#include "design/kernel_model.hpp"
#include "design/psf.hpp"
#include "design/psf_exact.hpp"
#include "design/working_distance.hpp"
#include "io/mask_json.hpp"
#include "optimize/scenes.hpp"
#include "optimize/simulate.hpp"

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
    std::string geometry = "integer";            // exact: design/psf_exact over the sensor
    std::optional<std::string> object_distance;  // exact: u, default the mask's
    std::optional<std::string> size;             // exact: ROWSxCOLS window, default the sensor
    std::uint64_t seed = 1;
    std::string dark_frame;
    std::string output;
    bool allow_violations = false;
    bool json = false;
    bool explain = false;
    int threads = 0;  // FFTW threads for >= 512 x 512 transforms; 0: all cores
};

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string lower_ext(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

void check_image_extension(const std::string& path, const std::string& flag) {
    const std::string ext = lower_ext(path);
    if (ext != ".tif" && ext != ".tiff" && ext != ".png" && ext != ".npy") {
        throw invalid_field(flag, path, "must end in .tif, .tiff (float32), .png (16-bit) or .npy");
    }
    const fs::path dir = fs::path(path).parent_path();
    if (!dir.empty() && !fs::is_directory(dir)) {
        throw invalid_field(flag, path, "the output directory does not exist");
    }
}

// Writes `image` to tmp in the format of final_path's extension (already checked): float32 TIFF,
// 16-bit PNG of [0, 1], float32 npy (core/image_io write_image).
void write_image_as(const fs::path& tmp, const fs::path& final_path, const Image& image) {
    const std::string ext = lower_ext(final_path);
    if (ext == ".png") {
        write_png(tmp, image, 16);
    } else if (ext == ".npy") {
        write_npy(tmp, image, SampleFormat::kFloat32);
    } else {
        write_tiff(tmp, image, SampleFormat::kFloat32);
    }
}

// The noise model from the flags; `explain` gets a line per noise stage that is not applied.
NoiseModel noise_from_flags(const SimulateOptions& o, const CLI::App& cmd,
                            std::vector<std::string>& explain) {
    if (o.photons) {
        if (cmd.count("--snr") > 0) {
            throw invalid_field("--snr", o.snr, "cannot be combined with --photons");
        }
        return photon_model(*o.photons, o.sensor_flags, &explain);
    }
    refuse_sensor_flags_without_photons(cmd);
    NoiseModel m;
    if (o.snr == "inf" || o.snr == "+inf") {
        m.kind = NoiseKind::kNone;
        explain.push_back("noise skipped: --snr inf (noiseless capture)");
        return m;
    }
    m.kind = NoiseKind::kGaussianSnr;
    m.snr_db = parse_number(o.snr, "--snr");
    return m;
}

void run(const SimulateOptions& o, const CLI::App& cmd) {
    std::vector<std::string> explain, noise_notes;
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
    if (o.sensor && !o.full_sensor) {
        throw invalid_field("--sensor", *o.sensor, "only applies with --full-sensor");
    }
    SimulationOptions sim;
    sim.noise = noise_from_flags(o, cmd, noise_notes);
    sim.seed = o.seed;
    sim.dark_frame = !o.dark_frame.empty();
    if (sim.dark_frame && sim.noise.kind != NoiseKind::kPhoton) {
        throw invalid_field("--dark-frame", o.dark_frame,
                            "needs the photon model (--photons N): the --snr model has no leak, "
                            "dark current or read noise to record");
    }
    SceneSpec scene_spec = scene_from_name(o.scene);

    io::MaskReadOptions ro;
    ro.allow_spacing_violations = o.allow_violations;
    const Mask mask = io::read_mask_file(o.mask, ro);
    const Kernel kernel = mask_kernel(mask);
    const int ppc = mask.psf.pixels_per_cell;
    const Plane psf = synthesize_psf(mask.pattern, kernel, ppc);
    const int m = static_cast<int>(psf.rows());
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const int cells = mask.pattern.n * mask.pattern.n;
    explain.push_back("psf: synthesised from the mask, " + std::to_string(m) + " x " +
                      std::to_string(m) + " pixels per period, kernel " +
                      kernel_model_name(kernel.model) + " (" + kernel.model_reason + ")");
    const Image scene = make_scene(scene_spec, m, m);
    explain.push_back("scene: " + scene_name(scene_spec) + " rendered at one " + std::to_string(m) +
                      " x " + std::to_string(m) + " period, " + std::to_string(scene.n_channels()) +
                      " channel(s)");
    explain.push_back("capture: circular convolution scene (*) PSF over one period");

    sim.full_sensor = o.full_sensor;
    if (o.full_sensor) {
        sim.sensor_cols = mask.camera.sensor_cols;
        sim.sensor_rows = mask.camera.sensor_rows;
        if (o.sensor) {
            const Size2 s = parse_size(*o.sensor, "--sensor");
            sim.sensor_cols = s.cols;
            sim.sensor_rows = s.rows;
        }
    } else {
        explain.push_back(
            "full-sensor tiling skipped: --full-sensor not given, one period suffices (any one "
            "full period decodes the scene)");
    }
    Plane exact;  // exact geometry: what the sensor records (design/psf_exact.hpp)
    if (o.geometry == "exact") {
        if (o.full_sensor || o.sensor) {
            throw invalid_field(o.full_sensor ? "--full-sensor" : "--sensor", "given",
                                "--geometry exact always covers the sensor (or --size ROWSxCOLS)");
        }
        ExactPsfOptions eo;
        eo.object_distance_m =
            o.object_distance
                ? parse_length_m(*o.object_distance, "--object-distance", AllowInfinity::kYes)
                : mask.camera.object_distance_m;
        check_object_distance(mask.camera, eo.object_distance_m, "--object-distance");
        if (o.size) {
            const Size2 rc = parse_size(*o.size, "--size");  // typed ROWSxCOLS
            eo.rows = rc.cols;
            eo.cols = rc.rows;
        }
        exact = exact_psf(mask, eo);
        sim.exact_psf = &exact;
        explain.push_back("geometry: exact at u = " + format_length(eo.object_distance_m) + ", " +
                          std::to_string(exact.rows()) + " x " + std::to_string(exact.cols()) +
                          " px, scene (*) exact PSF by linear convolution (the cyclic capture "
                          "above is replaced)");
    } else if (o.object_distance || o.size) {
        throw invalid_field(o.size ? "--size" : "--object-distance",
                            o.size ? *o.size : *o.object_distance, "only with --geometry exact");
    }
    const SimulatedCapture s = simulate_capture(scene, psf, holes, cells, sim);
    if (o.full_sensor) {
        explain.push_back("full-sensor tiling: the period repeated over " +
                          std::to_string(sim.sensor_cols) + " x " +
                          std::to_string(sim.sensor_rows) +
                          " pixels (periodic extension, exact "
                          "for the cyclic model), period origin at column " +
                          std::to_string(s.origin.col) + ", row " + std::to_string(s.origin.row) +
                          " so the centred crop is the period");
        if (!s.whole_period_on_sensor) {
            std::cerr << "pinmask simulate: warning: the sensor is smaller than one " << m << " x "
                      << m << " period: no full period to decode\n";
        }
    }
    switch (sim.noise.kind) {
        case NoiseKind::kNone:
            break;
        case NoiseKind::kGaussianSnr:
            explain.push_back("noise: Gaussian at " + fmt(sim.noise.snr_db) +
                              " dB SNR, one draw per pixel (seed " + std::to_string(o.seed) + ")");
            break;
        case NoiseKind::kPhoton: {
            const NoiseModel& nm = sim.noise;
            std::string stages = "Poisson signal";
            if (o.sensor_flags.optical_density)
                stages += " + film leak (OD " + fmt(nm.film_optical_density) + ")";
            if (o.sensor_flags.dark_current) stages += " + dark current";
            if (o.sensor_flags.read_noise) stages += ", read noise";
            if (o.sensor_flags.full_well) stages += ", saturation";
            if (o.sensor_flags.bits) stages += ", " + std::to_string(nm.adc_bits) + "-bit ADC";
            explain.push_back("noise: photon model, " + fmt(nm.photons_per_pinhole) +
                              " e per pinhole, " + stages + " (seed " + std::to_string(o.seed) +
                              ")");
            if (s.background[0] > 0.0) {
                explain.push_back(
                    "background: the expected leak + dark current stays in the "
                    "capture (" +
                    fmt(s.background[0]) + " in channel 0), as a real sensor records it");
            }
            break;
        }
    }
    explain.insert(explain.end(), noise_notes.begin(), noise_notes.end());
    explain.push_back(sim.dark_frame ? "dark frame: all-opaque film, same exposure, seed stream 1"
                                     : "dark frame skipped: --dark-frame not given");

    // PNG holds [0, 1]: report clipping rather than hide it.
    for (const auto& [path, img] : {std::pair{o.output, &s.capture}, {o.dark_frame, &s.dark}}) {
        if (path.empty() || lower_ext(path) != ".png") continue;
        double lo = 0.0, hi = 0.0;
        for (const Plane& ch : img->channels) {
            lo = std::min(lo, ch.minCoeff());
            hi = std::max(hi, ch.maxCoeff());
        }
        if (lo < 0.0 || hi > 1.0) {
            std::cerr << "pinmask simulate: warning: " << path << ": values in [" << lo << ", "
                      << hi
                      << "] are clipped to [0, 1] in a PNG; use .tiff or .npy for raw "
                         "float values\n";
        }
    }

    const std::string config_path = o.output + ".config.json";
    ordered_json background = ordered_json::array();
    for (double b : s.background) background.push_back(b);
    ordered_json config = {
        {"format", "pinmask-simulate-config"},
        {"version", 1},
        {"mask",
         {{"path", o.mask},
          {"geometry_hash", geometry_hash(mask)},
          {"n", mask.pattern.n},
          {"holes", holes},
          {"pixels_per_cell", ppc}}},
        {"psf",
         {{"period_px", m},
          {"kernel", kernel_model_name(kernel.model)},
          {"kernel_reason", kernel.model_reason},
          {"kernel_enclosed_energy", kernel.enclosed_energy},
          {"kernel_support_capped", kernel.support_capped},
          {"centring", "central element (floor(m/2), floor(m/2)) is the zero shift (deconvwnr)"}}},
        {"scene",
         {{"name", scene_name(scene_spec)},
          {"rows", m},
          {"cols", m},
          {"channels", scene.n_channels()}}},
        {"forward_model", "cyclic: circular convolution over one period"},
        {"geometry", o.geometry},
        {"full_sensor",
         {{"enabled", o.full_sensor},
          {"rows", s.capture.rows()},
          {"cols", s.capture.cols()},
          {"period_origin_row", s.origin.row},
          {"period_origin_col", s.origin.col},
          {"whole_period_on_sensor", s.whole_period_on_sensor}}},
        {"noise", noise_json(sim.noise)},
        {"seed", o.seed},
        {"units", sim.noise.kind == NoiseKind::kPhoton
                      ? "electrons / (photons_per_pinhole * holes); a uniform noiseless scene "
                        "of value v gives v plus the background"
                      : "normalised: a uniform noiseless scene of value v gives v"},
        {"background_per_channel", background},
        {"outputs",
         {{"capture", o.output},
          {"dark_frame", o.dark_frame.empty() ? ordered_json(nullptr) : ordered_json(o.dark_frame)},
          {"config", config_path}}},
        {"explain", explain}};

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
        std::cout << ordered_json{{"capture", o.output},
                                  {"config", config_path},
                                  {"dark_frame", o.dark_frame.empty() ? ordered_json(nullptr)
                                                                      : ordered_json(o.dark_frame)},
                                  {"rows", s.capture.rows()},
                                  {"cols", s.capture.cols()},
                                  {"channels", s.capture.n_channels()},
                                  {"period_px", m},
                                  {"noise", noise_json(sim.noise)},
                                  {"background_per_channel", background}}
                         .dump()
                  << "\n";
        return;
    }
    std::cout << "wrote " << o.output << " (" << s.capture.cols() << " x " << s.capture.rows()
              << ", " << s.capture.n_channels() << " channel(s))\n";
    if (!o.dark_frame.empty()) std::cout << "wrote " << o.dark_frame << " (dark frame)\n";
    std::cout << "wrote " << config_path << "\n";
}

constexpr const char* kFooter =
    "Model: the cyclic forward model over one period (DESIGN.md section 1): capture = scene (*) "
    "PSF, circular convolution with the PSF centred as `pinmask decode` expects, so decoding "
    "the capture with the mask returns the scene unshifted. --full-sensor repeats the period "
    "over the sensor: the periodic extension of the one-period capture, which is exact for the "
    "cyclic model; the period sits where the decoder's centred crop takes it. Noise is drawn per "
    "sensor pixel.\n"
    "Units: a uniform noiseless scene of value v gives v. Photon model: electrons / (N K), K the "
    "pinholes, plus a background (film leak + dark current) that the dark frame removes: "
    "`pinmask decode capture.tiff --dark dark.tiff ...`.\n"
    "Files: the capture (-o: .tif/.tiff float32, .png 16-bit clipped to [0, 1], .npy float32), "
    "OUT.config.json (the resolved configuration: mask, kernel, scene, noise, seed, tiling, "
    "units), and the dark frame when asked. All appear together or none does.\n"
    "Examples:\n"
    "  pinmask simulate m.mask.json --scene usaf --snr 30 -o capture.tiff\n"
    "  pinmask simulate m.mask.json --scene natural --photons 500 --read-noise 3 "
    "--dark-current 10 --optical-density 2 --full-sensor --dark-frame dark.tiff "
    "-o capture.tiff --explain";

void setup(CLI::App& app) {
    auto o = std::make_shared<SimulateOptions>();
    auto* cmd = app.add_subcommand(
        "simulate",
        "Simulate a capture of a scene through a mask: one period (or the whole sensor), with "
        "Gaussian SNR noise or a photon/sensor noise model, seeded and deterministic.");
    cmd->footer(kFooter);
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
                    "FFTW threads for transforms of >= 512 x 512 (default: all cores); the "
                    "capture does not depend on it")
        ->check(CLI::Range(1, 1024));
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
