// The score transaction: the metrics of one or more masks, one row per mask, only the groups
// asked for (optimize/metrics/mask_metrics, the set compare and search use). One call
// (run_score_request) for both faces: a request of typed settings in, the rows and the account of
// what was run out; io/score_json renders it. The faces read the masks and parse the noise and
// prior.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/mask_metrics.hpp"

namespace pinmask {

struct ScoreRequest {
    std::vector<Mask> masks;
    std::vector<std::string> names;  // each mask's label (its path), in the same order
    std::vector<std::string> metrics{"sidelobes", "spectrum", "analytic", "wiener"};
    std::vector<std::string> scenes{"letter-R", "usaf", "natural"};
    std::vector<NoiseLevel> noise;  // the levels (Gaussian SNRs or photon levels)
    std::string noise_text;         // the levels in words
    // The Gaussian SNRs (dB) both faces score at when no noise level is given.
    static inline const std::vector<double> kDefaultSnrDb{20.0, 30.0, 40.0};
    PriorSpec prior;
    std::string wiener_nsr = "0.01";  // a number > 0 or "tuned"
    std::string tv_lambda = "1e-3";   // a number > 0 or "tuned"
    int tv_iterations = 200;
    int noise_seeds = 1;
    std::uint64_t seed = 0;
    std::optional<std::string> robust;  // fabrication errors ("size=44um,jitter=2um")
    double depth_from_m = 0.0;          // 0: the working distance / 2
    double depth_to_m = 0.0;            // 0: twice the working distance
    bool explain = false;               // account for the prior's relevant frequencies too
    // Called before each mask's metrics: its index and the count.
    std::function<void(std::size_t index, std::size_t count)> progress;

    // The metric settings from the fields (InvalidInput naming the field at fault).
    MaskMetricsOptions options() const;
};

struct ScoreRow {
    std::string name;
    std::string geometry_hash;
    MaskMetrics metrics;
};

struct ScoreReport {
    std::vector<ScoreRow> rows;
    ScoreRequest request;  // as given, without its masks
    // The settings and the scene and prior caches of the run (the robust decoder's prior).
    std::shared_ptr<MetricsContext> context;
    // What was run, what was skipped and why, one line each (field references in backquotes).
    std::vector<std::string> explain;
};

ScoreReport run_score_request(ScoreRequest request);

}  // namespace pinmask
