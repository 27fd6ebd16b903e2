#include "design/optics/spectrum.hpp"

#include <cmath>

namespace pinmask {

std::vector<std::pair<double, double>> band_wavelengths(const Camera& camera) {
    validate(camera);
    const double lambda = camera.wavelength_m, fwhm = camera.bandwidth_m;
    if (fwhm == 0.0) return {{lambda, 1.0}};
    const double sigma = fwhm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
    const int half = kBandSamples / 2;
    const double step = 1.5 * fwhm / half;  // the outermost samples at +-1.5 FWHM
    std::vector<std::pair<double, double>> out;
    double total = 0.0;
    for (int k = -half; k <= half; ++k) {
        const double offset = k * step;
        const double weight = std::exp(-offset * offset / (2.0 * sigma * sigma));
        out.emplace_back(lambda + offset, weight);
        total += weight;
    }
    for (auto& [l, w] : out) w /= total;
    return out;
}

}  // namespace pinmask
