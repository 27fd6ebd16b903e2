// `pinmask search` over MPI ranks and with checkpoints: the flags --migrate-every,
// --checkpoint, --checkpoint-every and --resume, and how they fill the pipeline's island options
// (optimize/search/island_search) for the ranks of a RankComm (the executable passes the MPI world;
// this library never links MPI). Rank 0 reads --resume and broadcasts it, so every rank refuses
// a checkpoint of another configuration together (InvalidInput naming the differing keys).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "optimize/search/rank_comm.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::cli {

struct ClusterFlags {
    std::int64_t migrate_every = 0, checkpoint_every = 0;
    std::string checkpoint, resume;
};

void add_cluster_flags(CLI::App& cmd, ClusterFlags& f);

// The settings a checkpoint must share with the run that resumes it: the run's resolved
// configuration (search.config.json) without what does not change the chains' work ("time",
// "generator", "kernel_resolved"), plus "ranks", "migrate_every" and "checkpoint_every".
nlohmann::ordered_json checkpoint_config(nlohmann::ordered_json resolved, int ranks,
                                         const ClusterFlags& f);

// Sets p.comm and p.islands (collective: call on every rank). `config` is checkpoint_config();
// `output` the -o folder (the checkpoint may not be one of its files).
void setup_cluster(const ClusterFlags& f, RankComm& comm, const nlohmann::ordered_json& config,
                   const std::string& output, SearchPipelineOptions& p);

// Runs work(started) on this rank; work sets `started` once its set-up is done. Set-up errors
// are every rank's alike: rank 0 reports (the error is rethrown), the others leave silently with
// the same code. A later error may be one rank's: it is said on stderr with the rank, and
// abort_job(code) ends the job (the executable passes optimize/search/mpi's
// abort_job_if_distributed). On one rank every error is rethrown.
void run_on_ranks(RankComm& comm, const std::function<void(int)>& abort_job,
                  const std::function<void(bool& started)>& work);

}  // namespace pinmask::cli
