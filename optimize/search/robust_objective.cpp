#include "optimize/search/robust_objective.hpp"

#include "core/errors/error.hpp"

namespace pinmask {

RobustObjective::RobustObjective(ObjectiveWeights weights,
                                 std::shared_ptr<const RobustWienerModel> model,
                                 WienerFilterSpec filter, RobustObjectiveDecoder decoder)
    : weights_(weights), model_(std::move(model)), filter_(filter), decoder_(decoder) {
    weights_.validate();
    if (!model_) throw InvalidInput("the robust objective needs a robust Wiener model");
    ObjectiveWeights others = weights_;
    others.analytic_wiener = 0.0;
    if (others.max_sidelobe > 0.0 || others.sidelobe_energy > 0.0 || others.min_spectrum > 0.0) {
        others_ = std::make_unique<MaskObjective>(others, nullptr, filter_);
    }
}

RobustError RobustObjective::figure(const PatternState& s) const {
    return decoder_ == RobustObjectiveDecoder::kRobustFilter
               ? model_->evaluate_robust_filter(s.spectrum())
               : model_->evaluate(s.spectrum(), filter_);
}

double RobustObjective::evaluate(const PatternState& s) const {
    double total = others_ ? others_->evaluate(s) : 0.0;
    if (weights_.analytic_wiener > 0.0) {
        total -= weights_.analytic_wiener * figure(s).psnr_db;
    }
    return total;
}

std::map<std::string, double> RobustObjective::terms(const PatternState& s) const {
    std::map<std::string, double> out;
    if (others_) out = others_->terms(s);
    const RobustError e = figure(s);
    out["analytic_wiener_psnr_db"] = e.nominal.psnr_db;
    out["analytic_wiener"] = -e.nominal.psnr_db;
    out["robust_wiener_psnr_db"] = e.psnr_db;
    out["robust_wiener"] = -e.psnr_db;
    out["objective"] = evaluate(s);
    return out;
}

}  // namespace pinmask
