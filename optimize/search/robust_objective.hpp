// The search objective of robust design: the expected Wiener PSNR under fabrication errors
// (optimize/metrics/robust_wiener.hpp) with the other weighted terms of MaskObjective.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/search/mask_objective.hpp"
#include "optimize/search/search.hpp"

namespace pinmask {

// The search objective of `--objective robust`: -weights.analytic_wiener x robust PSNR plus the
// other weighted terms of MaskObjective (sidelobes, min spectrum). Terms add the robust figure
// (robust_figure_name) beside the nominal one (analytic_figure_name of the filter; with the
// robust filter "analytic_robust_filter_nominal_psnr_db", the nominal capture decoded by it).
// kDesignFilter: the figure is evaluate(spectrum, filter) (the nominal PSF's filter, what
// `search --objective robust` optimises). kRobustFilter: evaluate_robust_filter (the decoder is
// part of the design; `filter` is then unused by the robust term).
enum class RobustObjectiveDecoder { kDesignFilter, kRobustFilter };

// The scores key of the robust figure: "analytic_robust_mmse_psnr_db" or
// "analytic_robust_wiener_psnr_db" (the design's filter, by its kind), or
// "analytic_robust_filter_psnr_db".
std::string robust_figure_name(const WienerFilterSpec& filter, RobustObjectiveDecoder decoder);

class RobustObjective : public SearchObjective {
  public:
    RobustObjective(ObjectiveWeights weights, std::shared_ptr<const RobustWienerModel> model,
                    WienerFilterSpec filter,
                    RobustObjectiveDecoder decoder = RobustObjectiveDecoder::kDesignFilter);
    double evaluate(const PatternState& state) const override;
    std::map<std::string, double> terms(const PatternState& state) const override;

  private:
    RobustError figure(const PatternState& state) const;

    ObjectiveWeights weights_;
    std::shared_ptr<const RobustWienerModel> model_;
    WienerFilterSpec filter_;
    RobustObjectiveDecoder decoder_;
    std::unique_ptr<MaskObjective> others_;  // the non-Wiener terms (null when all zero)
};

}  // namespace pinmask
