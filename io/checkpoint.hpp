// The search checkpoint file, written by `pinmask search --checkpoint FILE` every
// --checkpoint-every evaluations per chain and read by --resume FILE:
//   {"format": "pinmask-search-checkpoint", "version": 2,
//    "config": {the settings that decide the chains' work: compared key by key on resume},
//    "segment": boundaries passed (>= 1), "evaluations_between_boundaries": >= 1,
//    "chains": [every chain of every rank in global order:
//      {"rng": the generator's state (std::mt19937_64 text form), "evaluations",
//       "best_objective" (null: none yet), "next_log_at", "log": [[evaluations, best], ...],
//       "top_capacity", "top": [{"objective", "pattern"}], "start": null | pattern}],
//    "checksum": FNV-1a 64 (io/fnv1a) of the file's text with this value as 16 zeros}
// pattern: {"n", "tiles_rows", "tiles_cols", "min_spacing_cells", "pinholes": [[row, col], ...]}
// in the chain's own pinhole order. Numbers are written in their shortest round-trip form, so
// a resumed chain continues bit for bit. Errors are InvalidInput naming the key path. The
// checksum is checked before any field: an edited checkpoint is refused as edited; the fields
// are then checked one by one (and against the run, io/search_run_config and
// optimize/search/search).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "optimize/search/search.hpp"

namespace pinmask::io {

inline constexpr const char* kCheckpointFormat = "pinmask-search-checkpoint";
inline constexpr int kCheckpointVersion = 2;

struct SearchCheckpointFile {
    nlohmann::ordered_json config = nlohmann::ordered_json::object();
    std::int64_t segment = 0;
    std::int64_t every = 0;  // evaluations per chain between boundaries
    std::vector<ChainState> chains;
};

std::string checkpoint_to_json(const SearchCheckpointFile& c);
SearchCheckpointFile parse_checkpoint(const std::string& text);

// Atomic write (core/files/atomic_file): a crash leaves the previous checkpoint in place.
void write_checkpoint(const std::filesystem::path& path, const SearchCheckpointFile& c);
// InvalidInput naming `resume` and the file when it cannot be read or parsed.
SearchCheckpointFile read_checkpoint(const std::filesystem::path& path);

// The top-level keys of two configurations whose values differ (or that only one has), sorted.
std::vector<std::string> differing_keys(const nlohmann::ordered_json& a,
                                        const nlohmann::ordered_json& b);

}  // namespace pinmask::io
