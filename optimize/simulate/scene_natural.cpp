// The natural scene: a seeded 1/f^alpha random texture (see scenes.hpp).
#include <algorithm>
#include <cmath>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {

Plane natural_scene(int rows, int cols, std::uint64_t seed, double alpha) {
    if (rows < 1 || cols < 1) {
        throw InvalidInput("scene size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    if (!std::isfinite(alpha) || alpha < 0.0) {
        throw invalid_field("alpha", std::to_string(alpha), "must be finite and >= 0");
    }
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    Plane white(rows, cols);
    for (Eigen::Index i = 0; i < white.size(); ++i) white.data()[i] = g(rng);
    const Fft2 fft(rows, cols);
    ComplexPlane spec = fft.forward(white);
    for (int k = 0; k < rows; ++k) {
        const double fy = static_cast<double>(std::min(k, rows - k)) / rows;
        for (int l = 0; l < fft.half_cols(); ++l) {
            const double fx = static_cast<double>(l) / cols;  // l <= cols/2: already the alias
            const double f = std::hypot(fy, fx);
            spec(k, l) *= (f == 0.0) ? 0.0 : std::pow(f, -alpha);
        }
    }
    Plane x = fft.inverse(spec);
    const double lo = x.minCoeff(), hi = x.maxCoeff();
    if (!(hi - lo > 0.0)) return Plane::Constant(rows, cols, 0.5);
    return (x - lo) / (hi - lo);
}

}  // namespace pinmask
