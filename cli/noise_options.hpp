// The sensor flags of the photon noise model (optimize/noise_model.hpp), shared by simulate and
// score: --read-noise, --dark-current, --full-well, --bits, --optical-density. The photon level
// itself (--photons) and the Gaussian --snr stay with each command, which may take one value or
// a list.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "optimize/mask_metrics.hpp"
#include "optimize/noise_model.hpp"

namespace pinmask::cli {

struct SensorFlags {
    std::optional<double> read_noise, dark_current, full_well, optical_density;
    std::optional<int> bits;
};

// Registers the five flags on cmd.
void add_sensor_flags(CLI::App& cmd, SensorFlags& flags);

// The photon model at `photons_per_pinhole` with the sensor flags, validated (InvalidInput
// naming the flag). `skipped`, when given, gets one line per stage the flags leave out.
NoiseModel photon_model(double photons_per_pinhole, const SensorFlags& flags,
                        std::vector<std::string>* skipped = nullptr);

// validate(model) with the flag in front of the field name: "--photons (photons_per_pinhole = ...".
void validate_naming_flags(const NoiseModel& model);

// InvalidInput when a sensor flag was given on cmd without the photon model.
void refuse_sensor_flags_without_photons(const CLI::App& cmd);

// The noise flags of score, compare and search: --snr LIST (Gaussian) or --photons LIST (the
// photon model) with the sensor flags.
struct NoiseFlags {
    std::string snr;      // default set by add_noise_flags
    std::string photons;  // empty: Gaussian
    SensorFlags sensor;
};

// Registers --snr (default `default_snr`), --photons and the sensor flags on cmd.
void add_noise_flags(CLI::App& cmd, NoiseFlags& flags, const std::string& default_snr);

// The levels the flags give (InvalidInput naming the flag); `text`, when given, gets a phrase
// for --explain and reports ("Gaussian noise at SNR 20,30 dB" / "the photon model at ...").
std::vector<NoiseLevel> noise_levels(const NoiseFlags& flags, const CLI::App& cmd,
                                     std::string* text = nullptr);

// Comma-separated items, none empty (InvalidInput naming flag otherwise).
std::vector<std::string> split_list(const std::string& text, const std::string& flag);

// {"kind": "none" | "gaussian-snr" | "photon", and the model's parameters}.
nlohmann::ordered_json noise_json(const NoiseModel& model);

}  // namespace pinmask::cli
