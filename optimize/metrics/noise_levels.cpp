#include "optimize/metrics/noise_levels.hpp"

#include <limits>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"

namespace pinmask {
namespace {

std::string list_text(const std::vector<double>& values) {
    std::string out;
    for (double v : values) out += (out.empty() ? "" : ",") + format_number(v);
    return out;
}

void check_count(const std::vector<double>& values, const std::string& field) {
    if (values.empty()) throw invalid_field(field, "''", "needs at least one item");
    if (values.size() > kMaxNoiseLevels) {
        throw invalid_field(field, "'" + list_text(values) + "'", "has more than 64 items");
    }
}

}  // namespace

void validate_naming_fields(const NoiseModel& m) {
    try {
        validate(m);
    } catch (const InvalidInput& e) {
        // NoiseModel's field -> the setting that fills it (NoiseLevelSettings, SensorSettings).
        static const std::pair<std::string, std::string> kNames[] = {
            {"photons_per_pinhole", field_ref("photons")},
            {"read_noise_e", field_ref("read_noise")},
            {"dark_current_e", field_ref("dark_current")},
            {"full_well_e", field_ref("full_well")},
            {"adc_bits", field_ref("bits")},
            {"film_optical_density", field_ref("optical_density")},
            {"snr_db", field_ref("snr_db")}};
        const std::string what = e.what();
        for (const auto& [model_field, setting] : kNames) {
            if (what.rfind(model_field + " = ", 0) == 0)
                throw InvalidInput(setting + " (" + what + ")");
        }
        throw;
    }
}

NoiseModel photon_model(double photons_per_pinhole, const SensorSettings& f,
                        std::vector<std::string>* skipped) {
    NoiseModel m;
    m.kind = NoiseKind::kPhoton;
    m.photons_per_pinhole = photons_per_pinhole;
    m.read_noise_e = f.read_noise.value_or(0.0);
    m.dark_current_e = f.dark_current.value_or(0.0);
    m.adc_bits = f.bits.value_or(0);
    m.full_well_e = f.full_well.value_or(std::numeric_limits<double>::infinity());
    m.film_optical_density = f.optical_density.value_or(std::numeric_limits<double>::infinity());
    if (f.bits && !f.full_well) {
        throw invalid_field(
            field_ref("bits"), std::to_string(*f.bits),
            "needs " + field_ref("full_well") + " E (the ADC full scale in electrons)");
    }
    validate_naming_fields(m);
    if (skipped) {
        auto note = [&](bool given, const std::string& line) {
            if (!given) skipped->push_back(line);
        };
        note(f.read_noise.has_value(),
             "read noise skipped: " + field_ref("read_noise") + " not given");
        note(f.dark_current.has_value(),
             "dark current skipped: " + field_ref("dark_current") + " not given");
        note(f.full_well.has_value(),
             "saturation skipped: " + field_ref("full_well") + " not given");
        note(f.bits.has_value(), "quantisation skipped: " + field_ref("bits") + " not given");
        note(f.optical_density.has_value(),
             "film leakage skipped: " + field_ref("optical_density") +
                 " not given (perfectly opaque film)");
    }
    return m;
}

void refuse_sensor_settings_without_photons(const SensorSettings& f) {
    const std::pair<bool, std::string> given[] = {
        {f.read_noise.has_value(), field_ref("read_noise")},
        {f.dark_current.has_value(), field_ref("dark_current")},
        {f.bits.has_value(), field_ref("bits")},
        {f.full_well.has_value(), field_ref("full_well")},
        {f.optical_density.has_value(), field_ref("optical_density")}};
    for (const auto& [is_given, field] : given) {
        if (is_given) {
            throw InvalidInput(field + ": a sensor parameter of the photon model; give " +
                               field_ref("photons") + " too (the " + field_ref("snr_db") +
                               " model is Gaussian noise at a fixed SNR)");
        }
    }
}

std::vector<NoiseLevel> noise_levels(const NoiseLevelSettings& s, std::string* text) {
    std::vector<NoiseLevel> out;
    if (!s.photons.empty()) {
        check_count(s.photons, field_ref("photons"));
        for (double ppp : s.photons) out.push_back(noise_level(photon_model(ppp, s.sensor)));
        const NoiseModel& m = out.front().model;
        if (text) {
            *text = "the photon model at " + list_text(s.photons) +
                    " electrons per pixel per pinhole (read noise " +
                    format_number(m.read_noise_e) + " e, dark current " +
                    format_number(m.dark_current_e) + " e, film OD " +
                    format_number(m.film_optical_density) + ")";
        }
        return out;
    }
    refuse_sensor_settings_without_photons(s.sensor);
    check_count(s.snr_db, field_ref("snr_db"));
    for (double snr : s.snr_db) {
        NoiseModel m;
        m.kind = NoiseKind::kGaussianSnr;
        m.snr_db = snr;
        validate_naming_fields(m);
        out.push_back(noise_level(m));
    }
    if (text) *text = "Gaussian noise at SNR " + list_text(s.snr_db) + " dB";
    return out;
}

}  // namespace pinmask
