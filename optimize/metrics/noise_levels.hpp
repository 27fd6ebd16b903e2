// The noise levels a user asks for, as data: Gaussian noise at a list of SNRs (dB) or the photon
// model (optimize/simulate/noise_model.hpp) at a list of photon levels with the sensor stages.
// Shared by simulate, score, compare, search and the Python module; errors name the settings'
// fields (snr_db, photons, read_noise, dark_current, full_well, bits, optical_density), which each
// face spells as its flag or keyword (core/errors/field_names.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

// The sensor stages of the photon model; an empty field leaves its stage out.
struct SensorSettings {
    std::optional<double> read_noise;       // rms read noise, electrons (>= 0)
    std::optional<double> dark_current;     // mean dark electrons per pixel (>= 0)
    std::optional<double> full_well;        // saturation, electrons (> 0)
    std::optional<double> optical_density;  // OD of the opaque film (transmission 10^-OD)
    std::optional<int> bits;                // ADC bit depth 1..24, needs full_well
};

// At most this many levels in one run.
inline constexpr std::size_t kMaxNoiseLevels = 64;

// The photon model at `photons_per_pinhole` electrons (per pixel through one pinhole for a
// uniform scene of value 1) with the sensor stages, validated (InvalidInput naming the field).
// `skipped`, when given, gets one line per stage the settings leave out.
NoiseModel photon_model(double photons_per_pinhole, const SensorSettings& sensor,
                        std::vector<std::string>* skipped = nullptr);

// validate(model) with the setting in front of the model's field: "`photons` (photons_per_pinhole
// = ...".
void validate_naming_fields(const NoiseModel& model);

// InvalidInput naming the first sensor setting given (the Gaussian model has no sensor stages).
void refuse_sensor_settings_without_photons(const SensorSettings& sensor);

// The levels of score, compare and search: the photon model at each of `photons` when it is not
// empty, else Gaussian noise at each of `snr_db`.
struct NoiseLevelSettings {
    std::vector<double> snr_db{30.0};  // dB, finite
    std::vector<double> photons;       // electrons per pixel per pinhole, > 0
    SensorSettings sensor;             // photon model only
};

// The levels (InvalidInput naming the field: an empty or over-long list, a bad value, sensor
// settings without photons). `text`, when given, gets a phrase for reports ("Gaussian noise at
// SNR 20,30 dB" / "the photon model at ...").
std::vector<NoiseLevel> noise_levels(const NoiseLevelSettings& settings,
                                     std::string* text = nullptr);

}  // namespace pinmask
