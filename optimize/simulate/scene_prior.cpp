#include "optimize/simulate/scene_prior.hpp"

#include <sstream>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {
namespace {

// Adds |X^|^2 of x to the full-spectrum accumulator using the half spectrum and Hermitian
// symmetry |X^(k, l)| = |X^(-k, -l)|.
void accumulate_power(const Fft2& fft, const Plane& x, Plane& acc, ComplexPlane& half) {
    fft.forward(x, half);
    const int rows = fft.rows(), cols = fft.cols(), hc = fft.half_cols();
    for (int k = 0; k < rows; ++k)
        for (int l = 0; l < cols; ++l) {
            acc(k, l) +=
                l < hc ? std::norm(half(k, l)) : std::norm(half((rows - k) % rows, cols - l));
        }
}

}  // namespace

ScenePrior natural_scene_prior(int rows, int cols, int count, std::uint64_t first_seed,
                               double alpha) {
    if (count < 1 || count > kMaxPriorSceneCount) {
        throw invalid_field(field_ref("prior.count"), std::to_string(count),
                            "must be between 1 and " + std::to_string(kMaxPriorSceneCount) +
                                " (sample scenes averaged for the prior; the average settles "
                                "long before)");
    }
    if (rows < 1 || cols < 1) {
        throw InvalidInput("prior size " + std::to_string(rows) + " x " + std::to_string(cols) +
                           ": both dimensions must be >= 1");
    }
    const Fft2 fft(rows, cols);
    ScenePrior prior;
    prior.power = Plane::Zero(rows, cols);
    ComplexPlane half;
    double mean_sum = 0.0;
    for (int i = 0; i < count; ++i) {
        const Plane x =
            natural_scene(rows, cols, first_seed + static_cast<std::uint64_t>(i), alpha);
        accumulate_power(fft, x, prior.power, half);
        mean_sum += x.mean();
    }
    prior.power /= count;
    prior.mean = mean_sum / count;
    prior.sample_count = count;
    std::ostringstream s;
    s << "natural alpha " << alpha << ", seeds " << first_seed << ".." << first_seed + count - 1;
    prior.source = s.str();
    return prior;
}

ScenePrior scene_prior_from_images(const std::vector<Plane>& images, std::string source) {
    if (images.empty()) throw InvalidInput("scene prior: no images given");
    const Eigen::Index rows = images[0].rows(), cols = images[0].cols();
    if (rows < 1 || cols < 1) throw InvalidInput("scene prior: empty image");
    const Fft2 fft(static_cast<int>(rows), static_cast<int>(cols));
    ScenePrior prior;
    prior.power = Plane::Zero(rows, cols);
    ComplexPlane half;
    double mean_sum = 0.0;
    for (std::size_t i = 0; i < images.size(); ++i) {
        const Plane& x = images[i];
        if (x.rows() != rows || x.cols() != cols) {
            throw InvalidInput("scene prior: image " + std::to_string(i) + " is " +
                               std::to_string(x.rows()) + " x " + std::to_string(x.cols()) +
                               ", image 0 is " + std::to_string(rows) + " x " +
                               std::to_string(cols) + ": sizes must match");
        }
        if (!x.isFinite().all()) {
            throw InvalidInput("scene prior: image " + std::to_string(i) +
                               " has non-finite values");
        }
        accumulate_power(fft, x, prior.power, half);
        mean_sum += x.mean();
    }
    const double count = static_cast<double>(images.size());
    prior.power /= count;
    prior.mean = mean_sum / count;
    prior.sample_count = static_cast<int>(images.size());
    prior.source = std::move(source);
    return prior;
}

}  // namespace pinmask
