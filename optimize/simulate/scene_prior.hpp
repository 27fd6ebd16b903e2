// Scene power-spectrum prior for the analytic error (optimize/metrics/analytic_error):
//   S(k) = E |X^(k)|^2,  X^ the unnormalised DFT (core/fft/fft.hpp) of a scene x of size rows x
//   cols,
// the expectation over a scene family, estimated by averaging |X^|^2 over sample scenes. S(0)
// carries the mean: S(0) = E[(sum x)^2] = N^2 E[mean(x)^2], N = rows * cols.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

struct ScenePrior {
    Plane power;           // rows x cols, S(k) for every frequency (full spectrum)
    double mean = 0.0;     // average of mean(x) over the sample scenes
    int sample_count = 0;  // scenes averaged
    std::string source;    // e.g. "natural alpha 1, seeds 0..15" or "3 images"

    int rows() const { return static_cast<int>(power.rows()); }
    int cols() const { return static_cast<int>(power.cols()); }
};

// The most sample scenes a prior averages: the average settles long before, and every face
// (the command's --prior-scenes, Python's prior_scenes) meets this one bound.
inline constexpr int kMaxPriorSceneCount = 4096;

// Average |X^|^2 over natural_scene(rows, cols, first_seed + i, alpha), i = 0 .. count-1
// (count in 1..kMaxPriorSceneCount, InvalidInput naming prior.count otherwise).
ScenePrior natural_scene_prior(int rows, int cols, int count, std::uint64_t first_seed = 0,
                               double alpha = 1.0);

// Average |X^|^2 over the given planes, all of one size (InvalidInput for none, empty,
// mismatched sizes or non-finite values). The caller resamples them to the period size.
ScenePrior scene_prior_from_images(const std::vector<Plane>& images, std::string source);

}  // namespace pinmask
