// Sensor noise models shared by the analytic error (optimize/metrics/analytic_error) and the
// forward simulation (optimize/simulate/simulate): the description, its per-pixel variance, and a
// sampler.
//
// Units and notation, once for this file. Captures are in *normalised units*: c = a (*) x, the
// scene x (values in [0, 1]) convolved over one period with the mask PSF a normalised to sum 1,
// so a uniform scene of value v gives c = v everywhere and mean(c) = mean(x). K is the number of
// open pinholes, n_cells = n^2 the cells of the pattern.
//
// Gaussian (kGaussianSnr): white noise of standard deviation sigma with
//     SNR dB = 10 log10(mean(c^2) / sigma^2)
// over the noiseless capture c. The SNR is fixed, so this model has no multiplexing trade-off.
//
// Photon (kPhoton), in electrons (e) per pixel:
//     signal  s = photons_per_pinhole * K * c              (Poisson)
//     leak    l = photons_per_pinhole * T * (n_cells - K) * mean(c)   (Poisson), T = 10^-OD:
//             the opaque film passes a fraction T of the light over its (n_cells - K) closed
//             cells; that light is not imaged by a pinhole and is modelled as a uniform field
//     dark    d = dark_current_e                          (Poisson)
//     read    Gaussian, standard deviation read_noise_e
//     full well: the electron count is clipped to full_well_e (saturation)
//     ADC:    adc_bits > 0 rounds to steps q = full_well_e / (2^adc_bits - 1) electrons and
//             clips to [0, full_well_e]; the analytic variance counts it as uniform noise q^2/12
// The expected offset l + d is removed (an ideal dark frame through all-opaque film, averaged
// over many frames) and the result divided by photons_per_pinhole * K, back to normalised
// units. The per-pixel variance in normalised units is therefore
//     var(c) = (ppp K c + l + d + read^2 + q^2/12) / (ppp K)^2,
// so the mean variance over a capture is var(mean(c)): the shot term falls like 1/K, the
// read, dark and quantisation terms like 1/K^2, while the PSF gets harder to invert as K grows
// (the multiplexing trade-off). Saturation is not part of the analytic variance (it is a
// clipping non-linearity); the sampler applies it.
#pragma once

#include <limits>
#include <random>

#include "core/image/image.hpp"

namespace pinmask {

// Bounds with their reasons (validate): electron counts per pixel (photons per pinhole, dark
// current, read noise) at most 1e12, a million times any pixel's full well, where counts times K
// stay exact in double precision; |SNR| at most 300 dB, where 10^(SNR/10) stays finite.
inline constexpr double kMaxElectrons = 1e12;
inline constexpr double kMaxAbsSnrDb = 300.0;
// Above this mean the sampler draws the normal approximation of the Poisson distribution.
inline constexpr double kPoissonNormalMean = 1e6;

enum class NoiseKind { kNone, kGaussianSnr, kPhoton };

struct NoiseModel {
    NoiseKind kind = NoiseKind::kGaussianSnr;
    double snr_db = 30.0;  // kGaussianSnr: 10 log10(mean(c^2) / sigma^2), dB
    // kPhoton: mean electrons per pixel through one pinhole for a uniform scene of value 1.
    double photons_per_pinhole = 1000.0;
    double read_noise_e = 0.0;    // rms read noise, electrons
    double dark_current_e = 0.0;  // mean dark-current electrons per pixel over the exposure
    int adc_bits = 0;             // 0: no quantisation; else 1..24, needs a finite full well
    double full_well_e = std::numeric_limits<double>::infinity();  // saturation, electrons
    // Optical density of the opaque film (transmission 10^-OD); +inf: perfectly opaque.
    double film_optical_density = std::numeric_limits<double>::infinity();
};

// Throws InvalidInput naming the first field out of range: finite SNR; photons_per_pinhole > 0
// and finite; read noise, dark current >= 0 and finite; adc_bits in 0..24 (> 0 needs a finite
// full well); full_well_e > 0; film_optical_density >= 0 (may be +inf). Fields of the other
// kind are not checked.
void validate(const NoiseModel& model);

// Fraction of light the opaque film passes: 10^-film_optical_density (0 for +inf).
double film_transmission(const NoiseModel& model);

// What the variance depends on besides the model: the noiseless capture's statistics (normalised
// units) and the pattern's open and total cell counts.
struct CaptureStats {
    double mean = 0.0;         // mean(c) = mean(scene)
    double mean_square = 0.0;  // mean(c^2)
    int open_cells = 1;        // K
    int total_cells = 1;       // n^2
};

// Gaussian sigma for a capture of mean square `mean_square` at `snr_db`.
double sigma_for_snr(double mean_square, double snr_db);

// Mean per-pixel noise variance in normalised units (formulas at the top of this file). For the
// photon model this is the variance at the mean capture value, which equals the pixel-average
// of the per-pixel variances because the variance is affine in c.
double mean_noise_variance(const NoiseModel& model, const CaptureStats& stats);

// Expected electrons per pixel removed by the ideal dark frame (leak + dark), photon model.
double dark_offset_e(const NoiseModel& model, const CaptureStats& stats);

// One noisy realisation of the clean capture (normalised units, same size), drawn from `rng`.
// Gaussian: sigma from mean(clean^2); photon: Poisson(signal + leak + dark) + read noise,
// saturation, ADC, then minus the expected offset and divided by ppp K. open_cells and
// total_cells are used by the photon model only. Throws InvalidInput for a clean capture with
// negative or non-finite values (photon model) or non-finite values (Gaussian).
Plane add_noise(const Plane& clean, const NoiseModel& model, int open_cells, int total_cells,
                std::mt19937_64& rng);

}  // namespace pinmask
