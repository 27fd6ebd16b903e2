// `pinmask search --json` from the search pipeline's summary (optimize/search/search_pipeline):
// the budget used, what each PSNR column is computed on, the ranked masks as written (their
// paths) with every score, the best mask per pinhole count and, for --objective robust-filter,
// the robust decoder's files. The command prints it; Python's search() returns it (with the
// masks and the run's log as values).
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
// Nothing written (Python's search() returns the masks as values): `output` "" and no paths,
// rendered as null.
nlohmann::ordered_json search_json(
    const SearchPipelineSummary& s, const std::string& output,
    const std::vector<std::filesystem::path>& paths,
    const std::optional<std::pair<std::string, std::string>>& robust_decoder = std::nullopt);

}  // namespace pinmask::io
