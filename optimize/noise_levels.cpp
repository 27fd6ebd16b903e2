#include "optimize/noise_levels.hpp"

#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace pinmask {
namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string list_text(const std::vector<double>& values) {
    std::string out;
    for (double v : values) out += (out.empty() ? "" : ",") + number(v);
    return out;
}

void check_count(const std::vector<double>& values, const std::string& flag) {
    if (values.empty()) throw invalid_field(flag, "''", "needs at least one item");
    if (values.size() > kMaxNoiseLevels) {
        throw invalid_field(flag, "'" + list_text(values) + "'", "has more than 64 items");
    }
}

}  // namespace

void validate_naming_flags(const NoiseModel& m) {
    try {
        validate(m);
    } catch (const InvalidInput& e) {
        static const std::pair<std::string, std::string> kNames[] = {
            {"photons_per_pinhole", "--photons"},
            {"read_noise_e", "--read-noise"},
            {"dark_current_e", "--dark-current"},
            {"full_well_e", "--full-well"},
            {"adc_bits", "--bits"},
            {"film_optical_density", "--optical-density"},
            {"snr_db", "--snr"}};
        const std::string what = e.what();
        for (const auto& [field, flag] : kNames) {
            if (what.rfind(field + " = ", 0) == 0) throw InvalidInput(flag + " (" + what + ")");
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
        throw invalid_field("--bits", std::to_string(*f.bits),
                            "needs --full-well E (the ADC full scale in electrons)");
    }
    validate_naming_flags(m);
    if (skipped) {
        auto note = [&](bool given, const std::string& line) {
            if (!given) skipped->push_back(line);
        };
        note(f.read_noise.has_value(), "read noise skipped: --read-noise not given");
        note(f.dark_current.has_value(), "dark current skipped: --dark-current not given");
        note(f.full_well.has_value(), "saturation skipped: --full-well not given");
        note(f.bits.has_value(), "quantisation skipped: --bits not given");
        note(f.optical_density.has_value(),
             "film leakage skipped: --optical-density not given (perfectly opaque film)");
    }
    return m;
}

void refuse_sensor_settings_without_photons(const SensorSettings& f) {
    const std::pair<bool, const char*> given[] = {
        {f.read_noise.has_value(), "--read-noise"},
        {f.dark_current.has_value(), "--dark-current"},
        {f.bits.has_value(), "--bits"},
        {f.full_well.has_value(), "--full-well"},
        {f.optical_density.has_value(), "--optical-density"}};
    for (const auto& [is_given, flag] : given) {
        if (is_given) {
            throw InvalidInput(std::string(flag) +
                               ": a sensor parameter of the photon model; give --photons too "
                               "(the --snr model is Gaussian noise at a fixed SNR)");
        }
    }
}

std::vector<NoiseLevel> noise_levels(const NoiseLevelSettings& s, std::string* text) {
    std::vector<NoiseLevel> out;
    if (!s.photons.empty()) {
        check_count(s.photons, "--photons");
        for (double ppp : s.photons) out.push_back(noise_level(photon_model(ppp, s.sensor)));
        const NoiseModel& m = out.front().model;
        if (text) {
            *text = "the photon model at " + list_text(s.photons) +
                    " electrons per pixel per pinhole (read noise " + number(m.read_noise_e) +
                    " e, dark current " + number(m.dark_current_e) + " e, film OD " +
                    number(m.film_optical_density) + ")";
        }
        return out;
    }
    refuse_sensor_settings_without_photons(s.sensor);
    check_count(s.snr_db, "--snr");
    for (double snr : s.snr_db) {
        NoiseModel m;
        m.kind = NoiseKind::kGaussianSnr;
        m.snr_db = snr;
        validate_naming_flags(m);
        out.push_back(noise_level(m));
    }
    if (text) *text = "Gaussian noise at SNR " + list_text(s.snr_db) + " dB";
    return out;
}

}  // namespace pinmask
