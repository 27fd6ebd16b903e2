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

// InvalidInput when a sensor flag was given on cmd without the photon model.
void refuse_sensor_flags_without_photons(const CLI::App& cmd);

// {"kind": "none" | "gaussian-snr" | "photon", and the model's parameters}.
nlohmann::ordered_json noise_json(const NoiseModel& model);

}  // namespace pinmask::cli
