// The sensor flags of the photon noise model (optimize/simulate/noise_model.hpp), shared by
// simulate and score: --read-noise, --dark-current, --full-well, --bits, --optical-density. The
// photon level itself (--photons) and the Gaussian --snr stay with each command, which may take one
// value or a list.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/noise_levels.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask::cli {

// The sensor settings as parsed (optimize/metrics/noise_levels.hpp).
using SensorFlags = SensorSettings;

// Registers the five flags on cmd.
void add_sensor_flags(CLI::App& cmd, SensorFlags& flags);

using pinmask::photon_model;
using pinmask::validate_naming_fields;

// InvalidInput when a sensor flag was given on cmd without the photon model.
void refuse_sensor_flags_without_photons(const CLI::App& cmd);

// One noise model from --snr (a number, or inf: noiseless) or --photons with the sensor flags (not
// both); `notes` gets a line per noise stage that is not applied.
NoiseModel one_noise_model(const std::string& snr, const std::optional<double>& photons,
                           const SensorFlags& sensor, const CLI::App& cmd,
                           std::vector<std::string>& notes);

// The noise flags of score, compare and search: --snr LIST (Gaussian) or --photons LIST (the
// photon model) with the sensor flags.
struct NoiseFlags {
    std::string snr;      // default set by add_noise_flags
    std::string photons;  // empty: Gaussian
    SensorFlags sensor;
};

// Registers --snr (default `default_snr`), --photons and the sensor flags on cmd.
void add_noise_flags(CLI::App& cmd, NoiseFlags& flags, const std::string& default_snr);

// The levels the flags give (optimize/metrics/noise_levels over the parsed lists; InvalidInput
// naming the flag); `text`, when given, gets a phrase for --explain and reports ("Gaussian noise at
// SNR 20,30 dB" / "the photon model at ...").
std::vector<NoiseLevel> noise_levels(const NoiseFlags& flags, const CLI::App& cmd,
                                     std::string* text = nullptr);

// Comma-separated items, none empty, at most max_items (InvalidInput naming flag otherwise).
std::vector<std::string> split_list(const std::string& text, const std::string& flag,
                                    std::size_t max_items = kMaxNoiseLevels);

}  // namespace pinmask::cli
