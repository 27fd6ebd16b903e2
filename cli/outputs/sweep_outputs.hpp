// What `pinmask sweep` writes into its -o folder: sweep.csv and sweep.md (one row per design
// point, in point order), points/point-NNNN.mask.json (the best mask of each point) and
// point-NNNN.search.config.json (the point as a `pinmask search --config` file), the plots of
// PSNR against K, pinhole size and light level (for the ones the sweep varies; SVG + PNG), and
// sweep.config.json (the sweep file as read). All or nothing: staged, then renamed.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/sweep_config.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/search/sweep.hpp"

namespace pinmask::cli {

// One point as run: its options, its resolved search configuration and its result.
struct SweepRow {
    const io::SweepPoint* point = nullptr;
    const SearchPipelineOptions* options = nullptr;
    nlohmann::ordered_json config;  // cli/options/search_options resolved_config of the point
    SweepPointResult result;
};

// The files the sweep writes, for planning before any work (no plot names: those depend on
// the results' axes and are checked when staged).
std::vector<std::filesystem::path> sweep_table_paths(const std::filesystem::path& dir,
                                                     std::size_t points);

// The Markdown table (also printed by the command).
std::string sweep_markdown(const io::SweepConfig& sweep, const std::vector<SweepRow>& rows);

// Writes everything; returns the plot files written (empty when no plotted axis varies).
std::vector<std::filesystem::path> write_sweep_outputs(const std::filesystem::path& dir,
                                                       const io::SweepConfig& sweep,
                                                       const std::vector<SweepRow>& rows);

}  // namespace pinmask::cli
