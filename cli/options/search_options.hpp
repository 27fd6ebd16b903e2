// The options of `pinmask search` as parsed, how --config FILE fills them, and the resolved
// configuration the run writes (search.config.json, read back by io/search_config).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/options/analytic_setup.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/noise_options.hpp"
#include "cli/options/psf_options.hpp"
#include "io/search_config.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::cli {

using io::kSearchGenerator;

struct SearchCliOptions {
    CameraOptions camera;
    GeometryOptions geometry;
    PsfOptions psf;
    std::string strategy = "anneal", time = "20s", filter = "auto", keep_out = "none";
    std::optional<std::int64_t> evals;
    std::optional<int> config_ranks;  // --config's "ranks": the rank count of the run that wrote it
    int threads = 0, top = 5;
    std::uint64_t seed = 1;
    NoiseFlags noise;
    PriorFlags prior;
    double w_analytic = 1.0, w_max_sidelobe = 0.0, w_sidelobe_energy = 0.0, w_min_spectrum = 0.0;
    double w_depth = 0.0, depth_from = 0.0, depth_to = 0.0;  // --depth-weight, --depth-from/to
    std::vector<std::string> rerank_scenes{"letter-R", "usaf", "siemens-star"};
    bool rerank_tv = true, no_rerank = false, allow_spectral_zeros = false, json = false,
         quiet = false, explain = false;
    std::string rank_by = "wiener", output, config;
    std::string objective = "nominal", robust;  // --objective, --robust
    std::string holes = "20";  // --holes K or A..B (geometry.holes is unused by search)
};

// The settings of --config FILE, for every option the command line did not give.
void apply_config(const io::SearchConfig& c, const CLI::App& cmd, SearchCliOptions& o);

// The flags of `pinmask search` but --config, registered on cmd (cli/cmd_search.cpp). `pinmask
// sweep` registers them on an unparsed app so apply_config fills every option from a point.
void add_search_flags(CLI::App* cmd, const std::shared_ptr<SearchCliOptions>& o);

// The pipeline options the flags give, validated; -o is not checked here (cli/cmd_search.cpp).
SearchPipelineOptions search_pipeline_options(const SearchCliOptions& o, const CLI::App& cmd);

// The resolved configuration of a run.
// "time" is null for an --evals run (no time budget), "ranks" the MPI rank count.
nlohmann::ordered_json resolved_config(const SearchCliOptions& o, const SearchPipelineOptions& p,
                                       const SearchPipelineSummary& s, int ranks = 1);

}  // namespace pinmask::cli
