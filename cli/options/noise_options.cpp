#include "cli/options/noise_options.hpp"

#include <sstream>

#include "core/errors/error.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {
namespace {

constexpr const char* kSensorFlags[] = {"--read-noise", "--dark-current", "--bits", "--full-well",
                                        "--optical-density"};

}  // namespace

void add_sensor_flags(CLI::App& cmd, SensorFlags& f) {
    cmd.add_option("--read-noise", f.read_noise,
                   "Photon model: rms read noise, electrons (default 0)");
    cmd.add_option("--dark-current", f.dark_current,
                   "Photon model: mean dark-current electrons per pixel over the exposure, "
                   "Poisson (default 0)");
    cmd.add_option("--full-well", f.full_well,
                   "Photon model: saturation, electrons (default: none)");
    cmd.add_option("--bits", f.bits,
                   "Photon model: ADC bit depth 1..24, steps of full-well / (2^bits - 1) "
                   "electrons; needs --full-well (default: no quantisation)");
    cmd.add_option("--optical-density", f.optical_density,
                   "Photon model: optical density OD of the opaque film (transmission 10^-OD); "
                   "its leak over the closed cells adds a uniform background (default: "
                   "perfectly opaque)");
}

std::vector<std::string> split_list(const std::string& text, const std::string& flag,
                                    std::size_t max_items) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ',')) {
        if (item.empty()) throw invalid_field(flag, "'" + text + "'", "has an empty list item");
        out.push_back(item);
    }
    if (out.empty()) throw invalid_field(flag, "''", "needs at least one item");
    if (out.size() > max_items) {
        throw invalid_field(flag, "'" + text + "'",
                            "has more than " + std::to_string(max_items) + " items");
    }
    return out;
}

void add_noise_flags(CLI::App& cmd, NoiseFlags& f, const std::string& default_snr) {
    f.snr = default_snr;
    auto* snr =
        cmd.add_option("--snr", f.snr, "Capture SNRs in dB, comma-separated (Gaussian noise)")
            ->capture_default_str();
    cmd.add_option("--photons", f.photons,
                   "The photon model instead of --snr: mean electrons per pixel through ONE "
                   "pinhole for a uniform scene of value 1, comma-separated levels (K pinholes "
                   "collect K times that: the multiplexing trade-off), with the sensor flags")
        ->excludes(snr);
    add_sensor_flags(cmd, f.sensor);
}

std::vector<NoiseLevel> noise_levels(const NoiseFlags& f, const CLI::App& cmd, std::string* text) {
    NoiseLevelSettings s;
    s.sensor = f.sensor;
    if (!f.photons.empty()) {
        if (cmd.count("--snr") > 0)
            throw invalid_field("--snr", f.snr, "cannot be combined with --photons");
        for (const std::string& item : split_list(f.photons, "--photons"))
            s.photons.push_back(parse_number(item, "--photons"));
    } else {
        refuse_sensor_flags_without_photons(cmd);
        s.snr_db.clear();
        for (const std::string& item : split_list(f.snr, "--snr"))
            s.snr_db.push_back(parse_number(item, "--snr"));
    }
    return pinmask::noise_levels(s, text);
}

void refuse_sensor_flags_without_photons(const CLI::App& cmd) {
    for (const char* flag : kSensorFlags) {
        if (cmd.count(flag) > 0) {
            throw InvalidInput(std::string(flag) +
                               ": a sensor parameter of the photon model; give --photons too "
                               "(the --snr model is Gaussian noise at a fixed SNR)");
        }
    }
}

NoiseModel one_noise_model(const std::string& snr, const std::optional<double>& photons,
                           const SensorFlags& sensor, const CLI::App& cmd,
                           std::vector<std::string>& notes) {
    if (photons) {
        if (cmd.count("--snr") > 0)
            throw invalid_field("--snr", snr, "cannot be combined with --photons");
        return photon_model(*photons, sensor, &notes);
    }
    refuse_sensor_flags_without_photons(cmd);
    NoiseModel m;
    if (snr == "inf" || snr == "+inf") {
        m.kind = NoiseKind::kNone;
        notes.push_back("noise skipped: --snr inf (noiseless capture)");
        return m;
    }
    m.kind = NoiseKind::kGaussianSnr;
    m.snr_db = parse_number(snr, "--snr");
    return m;
}

}  // namespace pinmask::cli
