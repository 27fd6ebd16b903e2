// The search objective (lower is better), a weighted sum of terms each of which is computed only
// when its weight is non-zero:
//   analytic_wiener   -expected Wiener PSNR in dB (optimize/metrics/analytic_error: closed form
//   from the
//                     OTF A^ = P^ K^, the scene prior and the noise model). evaluate() reads it
//                     from per-alias tables (optimize/metrics/aliased_wiener, built on first use
//                     for the pattern size): O(n^2) per call, within the tables' interpolation
//                     error of the direct O(m^2) sum that terms() reports.
//   max_sidelobe      max autocorrelation sidelobe / K (0 .. 1)
//   sidelobe_energy   integrated sidelobe level sum_{d != 0} R(d)^2 / K^2
//   min_spectrum      -min_{k != 0} |P^(k)| / sqrt(K)  (sqrt(K) is |P^| of a flat spectrum with
//                     the same energy, so the term is about -1 for a good pattern)
// terms() reports figures under the names score and compare give them (io/metrics_json.hpp),
// not the weighted terms above: analytic_mmse_psnr_db (the per-frequency optimal filter, always:
// the objective bound is stated against it), with a fixed or tuned NSR filter also
// analytic_wiener_psnr_db and analytic_wiener_nsr, max_sidelobe (R(d), not / K),
// integrated_sidelobe_level (the sidelobe_energy term), min_abs_pattern_spectrum (|P^|, not
// / sqrt(K)) and the weighted sum as "objective".
// The depth weight is optimize/search/depth_term's (DepthTermObjective wraps this objective or the
// robust one); MaskObjective itself does not evaluate it.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "optimize/metrics/aliased_wiener.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/search/search.hpp"

namespace pinmask {

struct ObjectiveWeights {
    double analytic_wiener = 1.0;
    double max_sidelobe = 0.0;
    double sidelobe_energy = 0.0;
    double min_spectrum = 0.0;
    double depth = 0.0;  // optimize/search/depth_term: W x 20 log10(worst relative depth bound), dB

    // Throws InvalidInput for a negative or non-finite weight, or when all are zero.
    void validate() const;
};

// The scores key of the analytic figure a search with `filter` optimises:
// "analytic_mmse_psnr_db" for the optimal filter, "analytic_wiener_psnr_db" for a fixed or tuned
// NSR.
std::string analytic_figure_name(const WienerFilterSpec& filter);

class MaskObjective : public SearchObjective {
  public:
    // `model` may be null only when weights.analytic_wiener == 0 (InvalidInput otherwise).
    MaskObjective(ObjectiveWeights weights, std::shared_ptr<const AnalyticWienerModel> model,
                  WienerFilterSpec filter);

    double evaluate(const PatternState& state) const override;
    std::map<std::string, double> terms(const PatternState& state) const override;

    const ObjectiveWeights& weights() const { return weights_; }

  private:
    // The per-alias tables for patterns of size n, built once (thread-safe).
    std::shared_ptr<const AliasedWiener> aliased(int n) const;

    ObjectiveWeights weights_;
    std::shared_ptr<const AnalyticWienerModel> model_;
    WienerFilterSpec filter_;
    mutable std::mutex aliased_mutex_;
    mutable std::shared_ptr<const AliasedWiener> aliased_;
};

}  // namespace pinmask
