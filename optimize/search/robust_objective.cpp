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

std::string robust_figure_name(const WienerFilterSpec& filter, RobustObjectiveDecoder decoder) {
    if (decoder == RobustObjectiveDecoder::kRobustFilter) return "analytic_robust_filter_psnr_db";
    return filter.kind == WienerFilterKind::kOptimal ? "analytic_robust_mmse_psnr_db"
                                                     : "analytic_robust_wiener_psnr_db";
}

std::map<std::string, double> RobustObjective::terms(const PatternState& s) const {
    std::map<std::string, double> out;
    if (others_) out = others_->terms(s);
    const RobustError e = figure(s);
    if (decoder_ == RobustObjectiveDecoder::kRobustFilter) {
        out["analytic_robust_filter_nominal_psnr_db"] = e.nominal.psnr_db;
    } else {
        out[analytic_figure_name(filter_)] = e.nominal.psnr_db;
        if (filter_.kind != WienerFilterKind::kOptimal) out["analytic_wiener_nsr"] = e.nominal.nsr;
    }
    out[robust_figure_name(filter_, decoder_)] = e.psnr_db;
    out["objective"] = evaluate(s);
    return out;
}

}  // namespace pinmask
