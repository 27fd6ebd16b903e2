#include "optimize/search/mask_objective.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/number_format.hpp"

namespace pinmask {
namespace {

struct SidelobeTerms {
    int max_sidelobe = 0;    // max_{d != 0} R(d)
    double max_ratio = 0.0;  // / K
    double energy = 0.0;
};

SidelobeTerms sidelobes(const PatternState& s) {
    const auto& r = s.autocorrelation();
    const double k = s.holes();
    int max_side = 0;
    double sum_sq = 0.0;
    for (std::size_t i = 1; i < r.size(); ++i) {
        max_side = std::max(max_side, r[i]);
        sum_sq += static_cast<double>(r[i]) * r[i];
    }
    return {max_side, max_side / k, sum_sq / (k * k)};
}

// min_{k != 0} |P^(k)| (0 for a 1 x 1 pattern, as spectrum_metrics).
double min_abs_spectrum(const PatternState& s) {
    const ComplexPlane& p = s.spectrum();
    double m = INFINITY;
    for (Eigen::Index i = 1; i < p.size(); ++i) m = std::min(m, std::abs(p.data()[i]));
    return p.size() > 1 ? m : 0.0;
}

double min_spectrum_ratio(const PatternState& s) {
    return min_abs_spectrum(s) / std::sqrt(static_cast<double>(s.holes()));
}

}  // namespace

void ObjectiveWeights::validate() const {
    const std::pair<const char*, double> all[] = {{"analytic_wiener", analytic_wiener},
                                                  {"max_sidelobe", max_sidelobe},
                                                  {"sidelobe_energy", sidelobe_energy},
                                                  {"min_spectrum", min_spectrum},
                                                  {"depth", depth}};
    bool any = false;
    for (const auto& [name, w] : all) {
        // Above 1e6 one term is the whole objective whatever the others are, and a huge weight
        // times a dB figure overflows to an infinite objective that ranks nothing.
        if (!std::isfinite(w) || w < 0.0 || w > 1e6) {
            throw invalid_field(field_ref(std::string("weights.") + name), format_number(w),
                                "must be finite, >= 0 and <= 1e6");
        }
        any = any || w > 0.0;
    }
    if (!any) throw InvalidInput("weights: every objective weight is zero; nothing to optimise");
}

MaskObjective::MaskObjective(ObjectiveWeights weights,
                             std::shared_ptr<const AnalyticWienerModel> model,
                             WienerFilterSpec filter)
    : weights_(weights), model_(std::move(model)), filter_(filter) {
    weights_.validate();
    if (weights_.analytic_wiener > 0.0 && !model_) {
        throw InvalidInput("weights.analytic_wiener > 0 needs an analytic Wiener model");
    }
}

std::shared_ptr<const AliasedWiener> MaskObjective::aliased(int n) const {
    const std::lock_guard<std::mutex> lock(aliased_mutex_);
    if (!aliased_ || aliased_->n() != n) {
        aliased_ = std::make_shared<const AliasedWiener>(model_, n, filter_);
    }
    return aliased_;
}

double MaskObjective::evaluate(const PatternState& s) const {
    double total = 0.0;
    if (weights_.analytic_wiener > 0.0) {
        total -= weights_.analytic_wiener * aliased(s.n())->evaluate(s.spectrum()).psnr_db;
    }
    if (weights_.max_sidelobe > 0.0 || weights_.sidelobe_energy > 0.0) {
        const SidelobeTerms t = sidelobes(s);
        total += weights_.max_sidelobe * t.max_ratio + weights_.sidelobe_energy * t.energy;
    }
    if (weights_.min_spectrum > 0.0) total -= weights_.min_spectrum * min_spectrum_ratio(s);
    return total;
}

std::string analytic_figure_name(const WienerFilterSpec& filter) {
    return filter.kind == WienerFilterKind::kOptimal ? "analytic_mmse_psnr_db"
                                                     : "analytic_wiener_psnr_db";
}

std::map<std::string, double> MaskObjective::terms(const PatternState& s) const {
    std::map<std::string, double> out;
    if (model_) {
        out["analytic_mmse_psnr_db"] =
            model_->evaluate(s.spectrum(), {WienerFilterKind::kOptimal, 0.0}).psnr_db;
        if (filter_.kind != WienerFilterKind::kOptimal) {
            const AnalyticError e = model_->evaluate(s.spectrum(), filter_);
            out["analytic_wiener_psnr_db"] = e.psnr_db;
            out["analytic_wiener_nsr"] = e.nsr;
        }
    }
    // Score's normalisation (optimize/metrics/autocorrelation, spectrum_metrics): the weighted
    // terms divide by K and sqrt(K), the reported figures do not.
    const SidelobeTerms t = sidelobes(s);
    out["max_sidelobe"] = t.max_sidelobe;
    out["integrated_sidelobe_level"] = t.energy;
    out["min_abs_pattern_spectrum"] = min_abs_spectrum(s);
    out["objective"] = evaluate(s);
    return out;
}

}  // namespace pinmask
