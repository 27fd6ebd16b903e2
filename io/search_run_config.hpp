// The resolved configuration of a search run (the search.config.json `pinmask search` writes,
// read back by io/search_config) and the part of it a checkpoint must share with the run that
// resumes it. Built from the pipeline options and the texts the run was given, so the command
// line and the Python module write the same file for the same settings, and a checkpoint of one
// resumes in the other.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "optimize/search/island_search.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::io {

// The settings as the run was given them where the pipeline options keep a parsed form.
struct SearchRunTexts {
    std::string strategy = "anneal", time = "20s", filter = "auto", keep_out = "none";
    std::string rank_by = "wiener", objective = "nominal", robust;
    std::uint64_t seed = 1;
    int top = 5;
    double w_analytic = 1.0, w_max_sidelobe = 0.0, w_sidelobe_energy = 0.0, w_min_spectrum = 0.0;
    double w_depth = 0.0;  // > 0: weights.depth and depth_range are written (else left out, so a
                           // run without the term writes what it wrote before the term existed)
    std::vector<std::string> rerank_scenes;  // as given; empty: no re-ranking
};

// The resolved configuration: "time" null for a run with an evaluation budget, "ranks" the
// process count, "kernel_resolved" the kernel the run used (empty before it ran).
nlohmann::ordered_json resolved_search_config(const SearchPipelineOptions& p,
                                              const SearchRunTexts& t,
                                              const std::string& kernel_resolved, int ranks);

// What a checkpoint records and a resume compares key by key: the resolved configuration without
// what does not change the chains' work ("time", "generator", "kernel_resolved"), with the rank
// count, the migration interval and the checkpoint interval.
nlohmann::ordered_json checkpoint_config(nlohmann::ordered_json resolved, int ranks,
                                         std::int64_t migrate_every, std::int64_t checkpoint_every);

// The island options' checkpoint callback: at each boundary, `config` and every chain's state
// written atomically to `path` (io/checkpoint). `path` is checked at once like any output
// (core/files/output_set check_output_path): InvalidInput naming `checkpoint`.
decltype(IslandOptions::checkpoint) checkpoint_writer(const std::filesystem::path& path,
                                                      const nlohmann::ordered_json& config);

// The checkpoint at `path` for resuming a run of `config`: InvalidInput naming `resume` when it
// cannot be read or is of another configuration (the differing keys named), or holds counts
// this run cannot have written. When it is `checkpoint`, the file this run writes its own
// checkpoints to, it stops being a protected input (core/files/output_set): the run supersedes it.
SearchCheckpointFile checkpoint_to_resume(const std::filesystem::path& path,
                                          const nlohmann::ordered_json& config,
                                          const std::filesystem::path& checkpoint = {});

}  // namespace pinmask::io
