#include "io/score_json.hpp"

#include "io/metrics_json.hpp"
#include "io/noise_json.hpp"

namespace pinmask::io {

nlohmann::ordered_json score_row_json(const ScoreRow& r) {
    const MaskMetrics& mm = r.metrics;
    nlohmann::ordered_json row;
    row["mask"] = r.name;
    row["geometry_hash"] = r.geometry_hash;
    row["n"] = mm.n;
    row["holes"] = mm.holes;
    row["pixels_per_cell"] = mm.pixels_per_cell;
    row["period_px"] = mm.period_px;
    nlohmann::ordered_json per_scene = nlohmann::ordered_json::object();
    metrics_json(mm, row, &per_scene);
    if (!per_scene.empty()) row["per_scene"] = per_scene;
    return row;
}

nlohmann::ordered_json score_json(const ScoreReport& report,
                                  const std::vector<nlohmann::ordered_json>& rows, bool explain) {
    const ScoreRequest& q = report.request;
    const MaskMetricsOptions& m = report.context->options();
    const auto joined = [](const std::vector<std::string>& items) {
        std::string s;
        for (const std::string& i : items) s += (s.empty() ? "" : ",") + i;
        return s;
    };
    nlohmann::ordered_json j;
    j["masks"] = rows;
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const NoiseLevel& level : m.noise) {
        nlohmann::ordered_json l = noise_json(level.model);
        l["key"] = level.key;
        levels.push_back(l);
    }
    j["settings"] = {{"metrics", joined(q.metrics)},
                     {"scenes", joined(q.scenes)},
                     {"noise", levels},
                     {"prior", m.prior.description()},
                     {"nsr", q.wiener_nsr},
                     {"tv_lambda", q.tv_lambda},
                     {"seeds", q.noise_seeds},
                     {"seed", q.seed},
                     {"tv_iterations", q.tv_iterations},
                     {"robust", m.robust.description()}};
    if (m.depth) {
        j["settings"]["depth_from_m"] = q.depth_from_m;  // 0: the working distance / 2
        j["settings"]["depth_to_m"] = q.depth_to_m;      // 0: twice the working distance
    }
    if (!m.noise.empty() && m.noise.front().model.kind != NoiseKind::kPhoton) {
        std::vector<double> snrs;
        for (const NoiseLevel& level : m.noise) snrs.push_back(level.model.snr_db);
        j["settings"]["snr_db"] = snrs;
    }
    if (explain) j["explain"] = report.explain;
    return j;
}

}  // namespace pinmask::io
