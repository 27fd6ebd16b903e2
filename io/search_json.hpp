// `pinmask search --json` from the search pipeline's summary (optimize/search/search_pipeline):
// the budget used, what each PSNR column is computed on, the ranked masks as written (their
// paths) with every score, the best mask per pinhole count and, for --objective robust-filter,
// the robust decoder's files.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "optimize/search/search_pipeline.hpp"

namespace pinmask::io {

// `paths`: the ranked masks' files, in rank order; `robust_decoder`: (psf .npy, NSR map .npy).
nlohmann::ordered_json search_json(
    const SearchPipelineSummary& s, const std::string& output,
    const std::vector<std::filesystem::path>& paths,
    const std::optional<std::pair<std::string, std::string>>& robust_decoder = std::nullopt);

}  // namespace pinmask::io
