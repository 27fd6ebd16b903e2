// The best pattern a search has found so far, kept on disk while it runs: OUT/best-so-far.mask.json
// (a mask file like rank-N.mask.json, family "search:<strategy> (best so far)", the objective
// in its scores). It exists for runs that are killed before their end: under Open MPI a second
// Ctrl-C to mpirun kills the ranks before rank 0 has gathered and written the chains; a single
// process killed by SIGKILL, or a machine that goes down, loses them too. The normal end (also
// after one Ctrl-C) writes the final files and removes it; so does a run that fails.
//
// Rank 0 keeps it, from its own chains and the patterns the cluster exchanges with it (a
// migration received): a thread of its own writes the best so far atomically
// (core/files/atomic_file) when it improved and at least `period_s` have passed since the last
// write (the first best is written at once), and at once after the first SIGINT/SIGTERM (the
// interrupt flag), before the ranks gather. Writing costs the search nothing: the chains only hand
// over an improved pattern under a mutex.
#pragma once

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "design/pattern/mask.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::cli {

// The file name inside the output folder.
inline constexpr const char* kBestSoFarName = "best-so-far.mask.json";

class BestSoFarSnapshot {
  public:
    // `tmpl`: the run's mask (camera, PSF, provenance seed and generator); its pattern is
    // replaced by each best. `interrupted` may be null.
    BestSoFarSnapshot(std::filesystem::path path, Mask tmpl, const std::atomic<bool>* interrupted,
                      double period_s = 2.0);
    // Without finish() (the run failed with an error): stops the thread and removes the file,
    // and the output folder when the snapshot made it and it is empty, so a failed run leaves
    // no file. Only a killed process (which runs no destructor) leaves the snapshot.
    ~BestSoFarSnapshot();
    BestSoFarSnapshot(const BestSoFarSnapshot&) = delete;
    BestSoFarSnapshot& operator=(const BestSoFarSnapshot&) = delete;

    // Thread-safe: keeps the pattern when it beats the best so far (lower is better).
    void offer(const Pattern& pattern, double objective);
    // Stops the thread and removes the file: the run's final outputs supersede it.
    void finish();
    // Files written so far (for the tests' and the docs' account).
    int writes() const { return writes_.load(); }

  private:
    void loop();
    void write(const Pattern& pattern, double objective);
    void stop();

    std::filesystem::path path_;
    Mask tmpl_;
    const std::atomic<bool>* interrupted_;
    double period_s_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<Pattern> best_;
    double best_objective_ = 0.0;
    bool fresh_ = false;  // best_ not yet written
    bool stopping_ = false;
    bool warned_ = false;  // a failed write was reported (once)
    bool finished_ = false;
    std::filesystem::path made_dir_;  // the output folder, when the first write created it
    std::atomic<int> writes_{0};
    std::thread thread_;
};

// A snapshot in dir/best-so-far.mask.json fed by the run `p` configures: what its chains find
// (p.search.on_improvement) and every chain's best at each checkpoint (p.islands.checkpoint,
// when the run keeps checkpoints). Its mask is p's template with the run's provenance.
std::unique_ptr<BestSoFarSnapshot> attach_best_so_far(SearchPipelineOptions& p,
                                                      const std::filesystem::path& dir,
                                                      const std::atomic<bool>* interrupted);

}  // namespace pinmask::cli
