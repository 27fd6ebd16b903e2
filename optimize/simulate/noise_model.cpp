#include "optimize/simulate/noise_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "core/errors/error.hpp"
#include "core/units/number_format.hpp"

namespace pinmask {
namespace {

// Poisson draw of mean `mean_e` > 0. Above kPoissonNormalMean the normal approximation
// N(mean, mean), rounded and clipped at 0: its skewness error 1/sqrt(mean) < 1e-3 is far below
// anything a capture can show, and std::poisson_distribution's rejection sampler loses its
// precision (and may never accept) for means near 2^53.
double poisson_draw(double mean_e, std::mt19937_64& rng, std::normal_distribution<double>& g) {
    if (mean_e <= kPoissonNormalMean) {
        std::poisson_distribution<long long> p(mean_e);
        return static_cast<double>(p(rng));
    }
    return std::max(0.0, std::round(mean_e + std::sqrt(mean_e) * g(rng)));
}

// ADC step in electrons, 0 when there is no quantisation.
double adc_step_e(const NoiseModel& m) {
    if (m.adc_bits <= 0) return 0.0;
    return m.full_well_e / (std::ldexp(1.0, m.adc_bits) - 1.0);
}

void check_counts(const CaptureStats& s) {
    if (s.open_cells < 1) {
        throw invalid_field("open_cells", std::to_string(s.open_cells), "must be >= 1");
    }
    if (s.total_cells < s.open_cells) {
        throw invalid_field("total_cells", std::to_string(s.total_cells),
                            "must be >= open_cells (" + std::to_string(s.open_cells) + ")");
    }
}

}  // namespace

void validate(const NoiseModel& m) {
    switch (m.kind) {
        case NoiseKind::kNone:
            return;
        case NoiseKind::kGaussianSnr:
            if (!(m.snr_db >= -kMaxAbsSnrDb && m.snr_db <= kMaxAbsSnrDb)) {
                throw invalid_field("snr_db", format_number(m.snr_db, 17),
                                    "must be between -300 and 300 dB (10^(SNR/10) leaves the "
                                    "range of double precision beyond that)");
            }
            return;
        case NoiseKind::kPhoton:
            break;
    }
    if (!(m.photons_per_pinhole > 0.0 && m.photons_per_pinhole <= kMaxElectrons)) {
        throw invalid_field("photons_per_pinhole", format_number(m.photons_per_pinhole, 17),
                            "must be > 0 and at most 1e12 electrons (a million times the full "
                            "well of any sensor pixel; electron counts stay exact in double "
                            "precision below that)");
    }
    if (!(m.read_noise_e >= 0.0 && m.read_noise_e <= kMaxElectrons)) {
        throw invalid_field("read_noise_e", format_number(m.read_noise_e, 17),
                            "must be >= 0 and at most 1e12 electrons");
    }
    if (!(m.dark_current_e >= 0.0 && m.dark_current_e <= kMaxElectrons)) {
        throw invalid_field("dark_current_e", format_number(m.dark_current_e, 17),
                            "must be >= 0 and at most 1e12 electrons (a million times the full "
                            "well of any sensor pixel)");
    }
    if (!(m.full_well_e > 0.0)) {
        throw invalid_field("full_well_e", format_number(m.full_well_e, 17),
                            "must be > 0 (inf: no saturation)");
    }
    if (m.adc_bits < 0 || m.adc_bits > 24) {
        throw invalid_field("adc_bits", std::to_string(m.adc_bits), "must be in 0..24");
    }
    if (m.adc_bits > 0 && !std::isfinite(m.full_well_e)) {
        throw invalid_field("adc_bits", std::to_string(m.adc_bits),
                            "quantisation needs a finite full_well_e (the ADC full scale)");
    }
    if (!(m.film_optical_density >= 0.0)) {
        throw invalid_field("film_optical_density", format_number(m.film_optical_density, 17),
                            "must be >= 0 (inf: perfectly opaque)");
    }
}

double film_transmission(const NoiseModel& m) {
    if (std::isinf(m.film_optical_density)) return 0.0;
    return std::pow(10.0, -m.film_optical_density);
}

double sigma_for_snr(double mean_square, double snr_db) {
    if (!(mean_square >= 0.0) || !std::isfinite(mean_square)) {
        throw invalid_field("mean_square_capture", format_number(mean_square, 17),
                            "must be finite and >= 0");
    }
    return std::sqrt(mean_square / std::pow(10.0, snr_db / 10.0));
}

double dark_offset_e(const NoiseModel& m, const CaptureStats& s) {
    check_counts(s);
    const double leak = m.photons_per_pinhole * film_transmission(m) *
                        static_cast<double>(s.total_cells - s.open_cells) * s.mean;
    return leak + m.dark_current_e;
}

double mean_noise_variance(const NoiseModel& m, const CaptureStats& s) {
    validate(m);
    switch (m.kind) {
        case NoiseKind::kNone:
            return 0.0;
        case NoiseKind::kGaussianSnr: {
            const double sigma = sigma_for_snr(s.mean_square, m.snr_db);
            return sigma * sigma;
        }
        case NoiseKind::kPhoton:
            break;
    }
    const double scale = m.photons_per_pinhole * s.open_cells;  // electrons per normalised unit
    const double q = adc_step_e(m);
    const double var_e =
        scale * s.mean + dark_offset_e(m, s) + m.read_noise_e * m.read_noise_e + q * q / 12.0;
    return var_e / (scale * scale);
}

Plane add_noise(const Plane& clean, const NoiseModel& m, int open_cells, int total_cells,
                std::mt19937_64& rng) {
    validate(m);
    if (!clean.isFinite().all()) {
        throw InvalidInput("add_noise: the clean capture has non-finite values");
    }
    if (m.kind == NoiseKind::kNone || clean.size() == 0) return clean;
    if (m.kind == NoiseKind::kGaussianSnr) {
        const double sigma = sigma_for_snr(clean.square().mean(), m.snr_db);
        std::normal_distribution<double> g(0.0, 1.0);
        Plane out(clean.rows(), clean.cols());
        for (Eigen::Index i = 0; i < clean.size(); ++i)
            out.data()[i] = clean.data()[i] + sigma * g(rng);
        return out;
    }
    if (clean.minCoeff() < 0.0) {
        throw InvalidInput("add_noise: photon noise needs a clean capture >= 0, found " +
                           format_number(clean.minCoeff(), 17));
    }
    CaptureStats stats{clean.mean(), clean.square().mean(), open_cells, total_cells};
    const double scale = m.photons_per_pinhole * open_cells;
    const double leak_e = dark_offset_e(m, stats) - m.dark_current_e;
    const double offset_e = leak_e + m.dark_current_e;
    const double q = adc_step_e(m);
    std::normal_distribution<double> g(0.0, 1.0);
    Plane out(clean.rows(), clean.cols());
    for (Eigen::Index i = 0; i < clean.size(); ++i) {
        const double mean_e = scale * clean.data()[i] + offset_e;
        double e = 0.0;
        if (mean_e > 0.0) e = poisson_draw(mean_e, rng, g);
        if (m.read_noise_e > 0.0) e += m.read_noise_e * g(rng);
        e = std::min(e, m.full_well_e);
        if (q > 0.0) e = std::clamp(std::round(e / q), 0.0, std::ldexp(1.0, m.adc_bits) - 1.0) * q;
        out.data()[i] = (e - offset_e) / scale;
    }
    return out;
}

}  // namespace pinmask
