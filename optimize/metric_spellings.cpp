#include "optimize/metric_spellings.hpp"

#include "core/error.hpp"
#include "core/units.hpp"

namespace pinmask {

WienerFilterSpec parse_wiener_filter(const std::string& text) {
    if (text == "optimal") return {WienerFilterKind::kOptimal, 0.0};
    if (text == "tuned") return {WienerFilterKind::kTunedNsr, 0.0};
    if (text.rfind("nsr:", 0) == 0) {
        const double nsr = parse_number(text.substr(4), "--filter nsr");
        if (!(nsr > 0.0)) throw invalid_field("--filter", text, "NSR must be > 0");
        return {WienerFilterKind::kFixedNsr, nsr};
    }
    throw invalid_field("--filter", text,
                        "expected 'optimal', 'tuned' or 'nsr:VALUE' (e.g. nsr:0.01)");
}

WienerFilterSpec parse_search_filter(const std::string& text, const NoiseModel& noise) {
    if (text == "auto") {
        return noise.kind == NoiseKind::kPhoton ? WienerFilterSpec{WienerFilterKind::kTunedNsr, 0.0}
                                                : WienerFilterSpec{WienerFilterKind::kOptimal, 0.0};
    }
    if (text != "optimal" && text != "tuned" && text.rfind("nsr:", 0) != 0) {
        throw invalid_field("--filter", text,
                            "expected 'auto', 'optimal', 'tuned' or 'nsr:VALUE' (e.g. nsr:0.01)");
    }
    return parse_wiener_filter(text);
}

WeightChoice parse_weight_choice(const std::string& text, const std::string& flag) {
    if (text == "tuned") return {true, 0.0};
    const double v = parse_number(text, flag);
    if (!(v > 0.0)) throw invalid_field(flag, text, "must be > 0 or 'tuned'");
    return {false, v};
}

std::vector<SceneSpec> scene_specs_from_names(const std::vector<std::string>& names) {
    std::vector<SceneSpec> specs;
    for (const std::string& item : names) {
        SceneSpec spec = scene_from_name(item);
        if (spec.kind == SceneKind::kNatural) spec.seed = 0;
        specs.push_back(spec);
    }
    return specs;
}

void set_decoder_flags(SimulatedMetricsOptions& sim, const std::string& nsr,
                       const std::string& tv_lambda, int tv_iterations) {
    sim.wiener_nsr = parse_weight_choice(nsr, "--nsr");
    sim.tv_lambda = parse_weight_choice(tv_lambda, "--tv-lambda");
    if (tv_iterations < 1) {
        throw invalid_field("--tv-iters", std::to_string(tv_iterations), "must be >= 1");
    }
    sim.tv_iterations = tv_iterations;
}

}  // namespace pinmask
