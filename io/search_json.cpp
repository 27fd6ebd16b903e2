#include "io/search_json.hpp"

#include <cmath>

namespace pinmask::io {

nlohmann::ordered_json search_json(
    const SearchPipelineSummary& s, const std::string& output,
    const std::vector<std::filesystem::path>& paths,
    const std::optional<std::pair<std::string, std::string>>& robust_decoder) {
    using Json = nlohmann::ordered_json;
    nlohmann::ordered_json j{{"output", output.empty() ? Json(nullptr) : Json(output)},
                             {"evaluations", s.search.evaluations},
                             {"evaluations_per_chain", s.search.evaluations_per_chain},
                             {"stop_reason", search_termination_name(s.termination)},
                             {"planned_s", s.planned_s},
                             {"used_s", s.used_s},
                             {"search_s", s.search_s},
                             {"rerank_s", s.rerank_s},
                             {"reranked", s.reranked}};
    std::string scenes;
    for (const std::string& n : s.rerank_scene_names) scenes += (scenes.empty() ? "" : ",") + n;
    j["objective_figure"] = s.objective_figure;
    j["psnr_columns"] = {
        {"analytic_mmse_psnr_db", "closed form over one period, prior " + s.prior_description +
                                      ", per-frequency optimal (MMSE) Wiener filter"},
        {"analytic_wiener_psnr_db", "closed form over one period, prior " + s.prior_description +
                                        ", Wiener filter at analytic_wiener_nsr (the search's "
                                        "filter, when it is not the optimal one)"},
        {"upper_bound_analytic_mmse_psnr_db",
         "the analytic MMSE PSNR no pattern with the mask's K can pass"},
        {"sim_wiener_psnr_db", "simulated on scenes " + scenes +
                                   " (cyclic model, the search's "
                                   "noise, noise seed = --seed), Wiener NSR tuned per mask"},
        {"sim_tv_psnr_db", "simulated on scenes " + scenes + ", TV-L2"}};
    j["reordered"] = s.reordered;
    for (std::size_t i = 0; i < s.ranked.size(); ++i) {
        nlohmann::ordered_json r{
            {"rank", i + 1},
            {"path", i < paths.size() ? Json(paths[i].string()) : Json(nullptr)},
            {"geometry_hash", geometry_hash(s.ranked[i].mask)},
            {"objective", s.ranked[i].objective},
            {"reranked", s.ranked[i].reranked}};
        for (const auto& [k, v] : s.ranked[i].mask.provenance.scores) r[k] = v;
        if (std::isfinite(s.ranked[i].upper_bound_psnr_db))
            r["upper_bound_analytic_mmse_psnr_db"] = s.ranked[i].upper_bound_psnr_db;
        j["ranked"].push_back(r);
    }
    for (const RankedMask& r : s.best_per_holes) {
        nlohmann::ordered_json row{{"holes", r.mask.pattern.pinholes.size()},
                                   {"objective", r.objective},
                                   {"spectral_zero", r.spectral_zero}};
        for (const auto& [k, v] : r.mask.provenance.scores) row[k] = v;  // analytic PSNR, terms
        if (std::isfinite(r.upper_bound_psnr_db))
            row["upper_bound_analytic_mmse_psnr_db"] = r.upper_bound_psnr_db;
        j["best_per_holes"].push_back(row);
    }
    if (robust_decoder)
        j["robust_decoder"] = {{"psf", robust_decoder->first}, {"nsr_map", robust_decoder->second}};
    return j;
}

}  // namespace pinmask::io
