#include "optimize/metrics/metric_spellings.hpp"

#include <algorithm>
#include <set>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/units/units.hpp"

namespace pinmask {

WienerFilterSpec parse_wiener_filter(const std::string& text) {
    if (text == "optimal") return {WienerFilterKind::kOptimal, 0.0};
    if (text == "tuned") return {WienerFilterKind::kTunedNsr, 0.0};
    if (text.rfind("nsr:", 0) == 0) {
        const double nsr = parse_number(text.substr(4), field_ref("filter") + " nsr");
        if (!(nsr > 0.0)) throw invalid_field(field_ref("filter"), text, "NSR must be > 0");
        return {WienerFilterKind::kFixedNsr, nsr};
    }
    throw invalid_field(field_ref("filter"), text,
                        "expected 'optimal', 'tuned' or 'nsr:VALUE' (e.g. nsr:0.01)");
}

WienerFilterSpec parse_search_filter(const std::string& text, const NoiseModel& noise) {
    if (text == "auto") {
        return noise.kind == NoiseKind::kPhoton ? WienerFilterSpec{WienerFilterKind::kTunedNsr, 0.0}
                                                : WienerFilterSpec{WienerFilterKind::kOptimal, 0.0};
    }
    if (text != "optimal" && text != "tuned" && text.rfind("nsr:", 0) != 0) {
        throw invalid_field(field_ref("filter"), text,
                            "expected 'auto', 'optimal', 'tuned' or 'nsr:VALUE' (e.g. nsr:0.01)");
    }
    return parse_wiener_filter(text);
}

WeightChoice parse_weight_choice(const std::string& text, const std::string& field) {
    if (text == "tuned") return {true, 0.0};
    const double v = parse_number(text, field);
    if (!(v > 0.0)) throw invalid_field(field, text, "must be > 0 or 'tuned'");
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

void set_decoder_settings(SimulatedMetricsOptions& sim, const std::string& nsr,
                          const std::string& tv_lambda, int tv_iterations) {
    sim.wiener_nsr = parse_weight_choice(nsr, field_ref("wiener_nsr"));
    sim.tv_lambda = parse_weight_choice(tv_lambda, field_ref("tv_lambda"));
    if (tv_iterations < 1) {
        throw invalid_field(field_ref("tv_iterations"), std::to_string(tv_iterations),
                            "must be >= 1");
    }
    sim.tv_iterations = tv_iterations;
}

const std::vector<std::string>& metric_group_names() {
    static const std::vector<std::string> names{"sidelobes", "spectrum", "analytic",
                                                "wiener",    "tv",       "depth"};
    return names;
}

void select_metrics(MaskMetricsOptions& m, const std::vector<std::string>& names) {
    if (names.empty()) throw invalid_field(field_ref("metrics"), "''", "name at least one metric");
    std::set<std::string> wanted;
    for (const std::string& s : names) {
        const auto& known = metric_group_names();
        if (std::find(known.begin(), known.end(), s) == known.end())
            throw invalid_field(field_ref("metrics"), s.empty() ? "''" : s,
                                "must be one of sidelobes, spectrum, analytic, wiener, tv, depth");
        wanted.insert(s);
    }
    m.sidelobes = wanted.count("sidelobes") > 0;
    m.spectrum = wanted.count("spectrum") > 0;
    m.analytic = wanted.count("analytic") > 0;
    m.wiener = wanted.count("wiener") > 0;
    m.tv = wanted.count("tv") > 0;
    m.depth = wanted.count("depth") > 0;
}

}  // namespace pinmask
