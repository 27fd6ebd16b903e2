#include "cli/search_cluster.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "io/checkpoint.hpp"
#include "io/search_run_config.hpp"
#include "optimize/search/byte_codec.hpp"
#include "optimize/search/chain_codec.hpp"

namespace pinmask::cli {

void add_cluster_flags(CLI::App& cmd, ClusterFlags& f) {
    cmd.add_option("--migrate-every", f.migrate_every,
                   "Island model: every this many evaluations per chain (at the chains' next "
                   "restart) each MPI rank sends its best pattern to the next rank on a ring; a "
                   "chain whose best is worse restarts from it (on one process: from the "
                   "process's best). 0: no migration")
        ->capture_default_str();
    cmd.add_option("--checkpoint", f.checkpoint,
                   "Checkpoint file: every chain's state (generator, patterns, counters) of all "
                   "ranks, written atomically by rank 0 every --checkpoint-every evaluations");
    cmd.add_option("--checkpoint-every", f.checkpoint_every,
                   "Evaluations per chain between checkpoints (at the chains' next restart)")
        ->capture_default_str();
    cmd.add_option("--resume", f.resume,
                   "Continue from a checkpoint of the same configuration (same flags, ranks, "
                   "threads); the result equals the uninterrupted run's")
        ->check(CLI::ExistingFile);
}

nlohmann::ordered_json checkpoint_config(nlohmann::ordered_json resolved, int ranks,
                                         const ClusterFlags& f) {
    return io::checkpoint_config(std::move(resolved), ranks, f.migrate_every, f.checkpoint_every);
}

void setup_cluster(const ClusterFlags& f, RankComm& comm, const nlohmann::ordered_json& config,
                   const std::string& output, SearchPipelineOptions& p) {
    p.comm = &comm;
    p.islands.migrate_every = f.migrate_every;
    p.islands.checkpoint_every = f.checkpoint_every;
    if (f.checkpoint_every > 0 && f.checkpoint.empty())
        throw InvalidInput("--checkpoint-every: needs --checkpoint FILE");
    if (!f.checkpoint.empty()) {
        if (f.checkpoint_every <= 0)
            throw InvalidInput("--checkpoint: needs --checkpoint-every E (evaluations per chain)");
        const std::filesystem::path path = f.checkpoint;
        if (std::filesystem::is_directory(path))
            throw invalid_field("--checkpoint", f.checkpoint, "is a directory, not a file name");
        const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : ".";
        if (!std::filesystem::is_directory(parent))
            throw invalid_field("--checkpoint", f.checkpoint, "its folder does not exist");
        // Not one of the run's own outputs (they are written at the end, over it).
        const std::filesystem::path out = std::filesystem::weakly_canonical(output);
        if (std::filesystem::weakly_canonical(path).parent_path() == out) {
            const std::string name = path.filename().string();
            if (name == "run-log.csv" || name == "summary.md" || name == "timing.csv" ||
                name == "search.config.json" || name == "best-so-far.mask.json" ||
                name.rfind("rank-", 0) == 0)
                throw invalid_field("--checkpoint", f.checkpoint,
                                    "is one of the output files of -o " + output);
        }
        if (p.search.max_evaluations == 0)
            throw InvalidInput(
                "--checkpoint: needs an evaluation budget (--evals); a --time run does not "
                "end at a reproducible point");
        p.islands.checkpoint = io::checkpoint_writer(path, config);
    }
    p.islands.validate();
    if (f.resume.empty()) return;
    // Rank 0 reads and checks the file; every rank gets the verdict and the chains:
    // [1, segment, encoded chains] or [0, message].
    Bytes message;
    if (comm.rank() == 0) {
        ByteWriter w;
        try {
            const io::SearchCheckpointFile c =
                io::checkpoint_to_resume(f.resume, config, f.checkpoint);
            w.u64(1);
            w.i64(c.segment);
            const Bytes chains = encode_chain_states(c.chains);
            message = w.take();
            message.insert(message.end(), chains.begin(), chains.end());
        } catch (const InvalidInput& e) {
            ByteWriter err;
            err.u64(0);
            err.str(e.what());
            message = err.take();
        }
    }
    comm.broadcast(message, 0);
    ByteReader r(message);
    if (r.u64() == 0) throw InvalidInput(r.str());
    p.islands.resume_segment = r.i64();
    const Bytes chains(message.begin() + 16, message.end());
    p.islands.resume = decode_chain_states(chains);
}

void run_on_ranks(RankComm& comm, const std::function<void(int)>& abort_job,
                  const std::function<void(bool& started)>& work) {
    bool started = false;
    try {
        work(started);
    } catch (const std::exception& e) {
        if (comm.size() == 1) throw;
        const int code = dynamic_cast<const InvalidInput*>(&e) ? 2 : 1;
        if (!started && comm.rank() == 0) throw;
        if (!started) std::exit(code);
        std::cerr << "pinmask search: rank " << comm.rank() << ": " << spell_flags(e.what())
                  << "\n";
        abort_job(code);
        throw;
    }
}

}  // namespace pinmask::cli
