// `pinmask depth MASK`: pitch, period, shift-invariance mismatch and the PSNR lost by decoding
// the exact-geometry capture with the mask's integer cyclic PSF, against object distance
// (optimize/metrics/depth_loss.hpp). Table on stdout, --json (one record per distance,
// io/depth_json), -o DIR (created when missing) for the plot (depth.svg + depth.png, written
// together) and the resolved configuration. Noise: the flags of score (--snr or --photons with the
// sensor flags), one level; Wiener NSR tuned as score tunes it unless --nsr gives a value.
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
#include "cli/options/noise_options.hpp"
#include "cli/outputs/progress.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/files/output_set.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "io/depth_json.hpp"
#include "io/mask_json.hpp"
#include "io/noise_json.hpp"
#include "optimize/metrics/depth_loss.hpp"
#include "optimize/metrics/metric_spellings.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

struct DepthCommandOptions {
    std::string mask;
    std::optional<std::string> distances;  // "1m,2m,6m,inf"
    std::optional<std::string> from, to;
    int steps = 8;
    NoiseFlags noise;
    std::string nsr = "tuned";
    std::uint64_t seed = 1;
    std::string scenes = "letter-R,natural";
    bool no_tv = false;
    std::string output_dir;
    bool json = false;
};

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item.empty()) throw invalid_field("list", "'" + s + "'", "has an empty item");
        out.push_back(item);
    }
    // getline drops what follows a last comma: "1m," would be read as one distance.
    if (!s.empty() && s.back() == ',')
        throw invalid_field("list", "'" + s + "'", "has an empty item (after its last comma)");
    return out;
}

std::vector<double> resolve_distances(const DepthCommandOptions& o, bool steps_given) {
    if (o.distances && (o.from || o.to || steps_given)) {
        throw invalid_field("--distances", *o.distances, "give either it or --from/--to/--steps");
    }
    if (o.distances) {
        std::vector<double> out;
        for (const std::string& t : split(*o.distances))
            out.push_back(parse_length_m(t, "--distances", AllowInfinity::kYes));
        if (out.size() > 1000) throw invalid_field("--distances", "too many", "at most 1000");
        return out;
    }
    if (!o.from || !o.to) {
        throw InvalidInput("depth needs --distances LIST, or --from A --to B [--steps N]");
    }
    return depth_range(parse_length_m(*o.from, "--from"),
                       parse_length_m(*o.to, "--to", AllowInfinity::kYes), o.steps);
}

void run(const DepthCommandOptions& o, const CLI::App& cmd) {
    const std::vector<double> distances = resolve_distances(o, cmd.count("--steps") > 0);
    if (!o.output_dir.empty()) check_output_folder(o.output_dir, "-o");
    DepthOptions d;
    d.scenes = split(o.scenes);
    std::string noise_text;
    if (o.noise.photons.empty() && (o.noise.snr == "inf" || o.noise.snr == "+inf")) {
        refuse_sensor_flags_without_photons(cmd);
        d.noise.kind = NoiseKind::kNone;
        noise_text = "no noise";
    } else {
        const std::vector<NoiseLevel> levels = noise_levels(o.noise, cmd, &noise_text);
        if (levels.size() != 1) {
            throw invalid_field(o.noise.photons.empty() ? "--snr" : "--photons",
                                o.noise.photons.empty() ? o.noise.snr : o.noise.photons,
                                "depth takes one noise level");
        }
        d.noise = levels.front().model;
    }
    d.wiener_nsr = parse_weight_choice(o.nsr, "--nsr");
    d.seed = o.seed;
    d.threads = fft_threads();  // the hardware threads, as the FFTs use
    d.with_tv = !o.no_tv;
    const Mask mask = io::read_mask_file(o.mask);
    ProgressLine bar("pinmask depth");
    bar.phase(std::string(d.wiener_nsr.tuned ? "tuning the Wiener NSR and decoding" : "decoding") +
              " the reference captures (" + std::to_string(d.scenes.size()) + " scene(s), " +
              noise_text + ")");
    d.progress = [&](std::size_t done, std::size_t total) {
        bar.update(double(done) / double(total),
                   std::to_string(done) + "/" + std::to_string(total) + " distances");
    };
    const std::vector<DepthRecord> records = depth_analysis(mask, distances, d);
    bar.finish();

    if (!o.output_dir.empty()) {
        const std::string title = "pinmask depth: " + fs::path(o.mask).filename().string() + " (" +
                                  noise_text + ", scenes " + o.scenes + ")";
        const nlohmann::ordered_json config{
            {"mask", o.mask},     {"noise", io::noise_json(d.noise)},
            {"nsr", o.nsr},       {"seed", o.seed},
            {"scenes", o.scenes}, {"tv", !o.no_tv}};
        const auto written = io::write_depth_files(o.output_dir, records,
                                                   mask.camera.object_distance_m, title, config);
        if (!o.json)
            for (const auto& p : written) std::cerr << "wrote " << p.string() << "\n";
    }
    if (o.json) {
        std::cout << io::depth_json(records).dump(2) << "\n";
        return;
    }
    std::printf("%s; Wiener NSR %s%s\n", noise_text.c_str(),
                format_number(records.front().wiener_nsr).c_str(),
                d.wiener_nsr.tuned ? " (tuned)" : "");
    std::printf("%12s %10s %10s %13s %14s %11s\n", "u", "px/cell", "period px", "mismatch px",
                "Wiener loss dB", "TV loss dB");
    for (const auto& r : records) {
        std::printf("%12s %10.4f %10.2f %13.3f %14s %11s\n",
                    format_length(r.object_distance_m).c_str(), r.pixels_per_cell, r.period_px,
                    r.lsi_mismatch_px, format_cell(r.wiener_psnr_loss_db).c_str(),
                    format_cell(r.tv_psnr_loss_db).c_str());
    }
}

constexpr const char* kFooter =
    "Per distance u: pixels per cell d |1 - f/f' + f/u| / w, the period n times that, the LSI "
    "mismatch n |pitch - the mask's pixels per cell| (px across one period), and the PSNR lost "
    "when the capture recorded at u (exact geometry: every pinhole at its true position, linear "
    "convolution) is decoded with the mask's integer cyclic PSF, against decoding the cyclic "
    "capture itself (same scenes, noise and decoder; TV lambda 1e-3). Noise as score: Gaussian "
    "--snr (one value, dB; inf: none) or the photon model --photons (electrons per pixel through "
    "one pinhole) with --read-noise, --dark-current, --full-well, --bits, --optical-density. The "
    "Wiener NSR is tuned once per run on the cyclic captures (as score --nsr tuned) unless --nsr "
    "gives it. Progress per distance on stderr (plain lines when stderr is not a terminal).\n"
    "Examples:\n"
    "  pinmask depth m.mask.json --distances 1m,2m,6m,inf\n"
    "  pinmask depth m.mask.json --from 0.9m --to 2m --steps 9 --photons 20 --read-noise 6\n"
    "  pinmask depth m.mask.json --from 2m --to inf --steps 6 -o depth_out --json";

void setup(CLI::App& app) {
    auto o = std::make_shared<DepthCommandOptions>();
    auto* cmd = app.add_subcommand(
        "depth",
        "Pitch, period, shift-invariance mismatch and decode PSNR loss against object "
        "distance, for a mask.");
    cmd->footer(kFooter);
    cmd->add_option("mask", o->mask, "Mask file (*.mask.json)")->required();
    cmd->add_option("--distances", o->distances,
                    "Object distances, comma-separated (e.g. 1m,6m,inf)");
    cmd->add_option("--from", o->from, "First distance of a range (e.g. 1m)");
    cmd->add_option("--to", o->to, "Last distance of a range (e.g. inf)");
    cmd->add_option("--steps", o->steps, "Points of the range, equally spaced in 1/u (2..1000)")
        ->capture_default_str();
    add_noise_flags(*cmd, o->noise, "30");
    // depth takes one level (score's flags take lists).
    cmd->get_option("--snr")->description(
        "Gaussian SNR of the simulated captures, dB, one value (inf: noiseless)");
    cmd->get_option("--photons")
        ->description(
            "The photon model instead of --snr: mean electrons per pixel through ONE pinhole for "
            "a uniform scene of value 1, one value, with the sensor flags");
    cmd->add_option("--nsr", o->nsr,
                    "Wiener noise-to-signal ratio (> 0), or 'tuned' (once per run, as score)")
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Base seed of the noise generators")->capture_default_str();
    cmd->add_option("--scenes", o->scenes, "Scenes, comma-separated (as simulate --scene)")
        ->capture_default_str();
    cmd->add_flag("--no-tv", o->no_tv, "Skip the TV decodes (Wiener only; faster)");
    cmd->add_option("-o,--output-dir", o->output_dir,
                    "Folder for depth.svg, depth.png and depth.json (written together; created "
                    "when missing)");
    cmd->add_flag("--json", o->json, "Print one JSON record per distance on stdout");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_depth(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
