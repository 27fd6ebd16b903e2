// What `pinmask search` writes into its output folder, all staged together (all or nothing):
//   rank-1.mask.json ... rank-N.mask.json   candidates, best first, with provenance and scores
//   run-log.csv                             seconds, evaluations, best_objective
//   summary.md                              the ranking table
//   search.config.json                      the resolved configuration of the run
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "design/mask.hpp"
#include "optimize/search.hpp"

namespace pinmask::cli {

struct RankedMask {
    Mask mask;
    double objective = 0.0;
    double sim_wiener_psnr_db = 0.0;  // NaN when re-ranking was skipped
    double sim_tv_psnr_db = 0.0;      // NaN when TV re-ranking was skipped
};

// Writes the folder's files; returns the mask paths in rank order.
std::vector<std::filesystem::path> write_search_outputs(const std::filesystem::path& dir,
                                                        const std::vector<RankedMask>& ranked,
                                                        const SearchSummary& summary,
                                                        const nlohmann::ordered_json& config);

// The Markdown ranking table (also printed by the command).
std::string search_summary_markdown(const std::vector<RankedMask>& ranked,
                                    const SearchSummary& summary);

}  // namespace pinmask::cli
