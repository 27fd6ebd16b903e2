#include "io/noise_json.hpp"

#include "io/json_strict.hpp"

namespace pinmask::io {

using json_strict::finite_or_null;

nlohmann::ordered_json noise_json(const NoiseModel& m) {
    switch (m.kind) {
        case NoiseKind::kNone:
            return {{"kind", "none"}};
        case NoiseKind::kGaussianSnr:
            return {{"kind", "gaussian-snr"},
                    {"snr_db", m.snr_db},
                    {"definition", "10 log10(mean(c^2) / sigma^2) over the noiseless capture"}};
        case NoiseKind::kPhoton:
            break;
    }
    return {{"kind", "photon"},
            {"photons_per_pinhole", m.photons_per_pinhole},
            {"read_noise_e", m.read_noise_e},
            {"dark_current_e", m.dark_current_e},
            {"full_well_e", finite_or_null(m.full_well_e)},
            {"adc_bits", m.adc_bits},
            {"film_optical_density", finite_or_null(m.film_optical_density)},
            {"film_transmission", film_transmission(m)}};
}

}  // namespace pinmask::io
