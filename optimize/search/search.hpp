// Mask search over cyclic patterns under the spacing rule: two strategies.
//   random: sample valid random patterns and keep the best (the paper's approach; the baseline).
//   anneal: simulated annealing moving one pinhole to a legal empty cell, fixed-length restarts.
//           With a pinhole-count range (min_holes..max_holes) a move may also add a
//           pinhole at a legal empty cell or remove one, so the chain chooses K; the best pattern
//           at every K evaluated is kept beside the overall top list.
// Chains are independent, one per thread, each with its own generator seeded from (seed, chain).
// With an evaluation budget the result is identical for the same seed and thread count. With a
// time budget the amount of work depends on the machine; the summary records the evaluations
// each chain made so the run can be repeated exactly with that evaluation budget.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "design/pattern/pattern.hpp"
#include "optimize/search/pattern_state.hpp"

namespace pinmask {

// What search minimises. Implementations must be thread-safe for concurrent const calls.
class SearchObjective {
  public:
    virtual ~SearchObjective() = default;
    // The objective of the state's pattern; lower is better.
    virtual double evaluate(const PatternState& state) const = 0;
    // The named terms behind evaluate() (for provenance and reports), names carry units.
    virtual std::map<std::string, double> terms(const PatternState& state) const = 0;
};

enum class SearchStrategy { kRandom, kAnneal };

struct SearchOptions {
    SearchStrategy strategy = SearchStrategy::kAnneal;
    int threads = 1;                   // independent chains, >= 1
    double time_budget_s = 20.0;       // wall-clock budget; 0 = none (then evaluations rule)
    std::int64_t max_evaluations = 0;  // per chain; 0 = none (then time rules)
    std::uint64_t seed = 1;
    int top = 5;                                // candidates returned, >= 1
    std::int64_t anneal_restart_moves = 20000;  // moves per annealing restart
    double anneal_final_temperature_ratio = 1e-3;
    std::vector<Cell> keep_out;    // cells no pinhole may occupy
    double log_interval_s = 0.25;  // run-log sampling period
    // Pinhole-count range: both 0 keeps K fixed (the sampler's K). Else 1 <= min_holes <=
    // max_holes: annealing adds and removes pinholes within the range, each with probability
    // resize_probability / 2 per move (when legal), and the best pattern per K is kept.
    int min_holes = 0, max_holes = 0;
    double resize_probability = 0.2;
    bool holes_range() const { return max_holes > 0; }
    // Called from a chain's thread each time that chain's best objective improves, with the
    // pattern (several chains call it at once: it must be thread-safe, and quick). It only
    // watches: the search's results do not depend on it. The command line keeps the best so far
    // on disk with it (cli/outputs/search_snapshot). Empty: not called.
    std::function<void(const Pattern& pattern, double objective)> on_improvement;

    // The bounds every face shares: evaluations per chain and candidates kept.
    static constexpr std::int64_t kMaxEvaluations = 1'000'000'000;
    static constexpr int kMaxTop = 1000;

    // Throws InvalidInput naming the field, value and rule.
    void validate() const;
};

struct Candidate {
    Pattern pattern;
    double objective = 0.0;
    std::map<std::string, double> terms;
};

// The best `capacity` distinct patterns seen by one chain, best first (ties by pattern). A plain
// value: copyable, so a chain's state can be checkpointed or exchanged between processes.
class TopCandidates {
  public:
    explicit TopCandidates(int capacity = 1) : capacity_(static_cast<std::size_t>(capacity)) {}

    double worst() const { return items_.size() < capacity_ ? INFINITY : items_.back().objective; }
    void offer(const Pattern& p, double objective) {
        if (objective >= worst()) return;
        std::vector<Cell> key = sorted_pinholes(p);
        for (const auto& it : items_) {
            if (it.key == key) return;
        }
        Item item{std::move(key), p, objective};
        const auto pos = std::upper_bound(items_.begin(), items_.end(), item,
                                          [](const Item& a, const Item& b) { return less(a, b); });
        items_.insert(pos, std::move(item));
        if (items_.size() > capacity_) items_.pop_back();
    }
    struct Item {
        std::vector<Cell> key;  // sorted pinholes
        Pattern pattern;
        double objective;
    };
    static bool less(const Item& a, const Item& b) {
        return a.objective < b.objective || (a.objective == b.objective && a.key < b.key);
    }
    const std::vector<Item>& items() const { return items_; }
    int capacity() const { return static_cast<int>(capacity_); }

  private:
    std::size_t capacity_;
    std::vector<Item> items_;
};

// Everything a chain carries from one annealing restart (or random draw) to the next, as a plain
// value type: its generator, counters, best-so-far log and top list. A chain can be stopped at a
// restart boundary, its state copied (checkpoint, MPI exchange) and resumed.
struct ChainState {
    std::mt19937_64 rng;
    std::int64_t evaluations = 0;
    double best_objective = INFINITY;
    std::int64_t next_checkpoint = 1;  // evaluation count of the next log entry
    std::vector<std::pair<std::int64_t, double>> checkpoints;  // (evaluations, best so far)
    TopCandidates top;
    // The start of the next annealing restart when set (a pattern migrated from another chain,
    // optimize/search/island_search); else the restart draws a random pattern. Unused by random
    // search.
    std::optional<Pattern> start;
    // Only with a pinhole-count range (SearchOptions::min_holes..max_holes): for every K the
    // chain evaluated, the best pattern at that K (a TopCandidates of capacity 1). Empty
    // otherwise.
    std::map<int, TopCandidates> best_per_holes;
};

// A search run in segments (for migration between processes and for checkpoints). Every chain
// pauses at its first restart boundary (between annealing restarts; between draws for random
// search) at or after (segment + 1) * every evaluations, or when it finishes; then at_boundary
// runs on the calling thread with every chain's state, may change them (ChainState::start) and
// says whether to go on. Pausing at a restart boundary changes nothing in a chain's work, so a
// segmented run equals an unsegmented one unless the hook changes a state.
struct SearchSegments {
    std::int64_t every = 0;          // evaluations per chain between boundaries, >= 1
    int first_chain = 0;             // chain c is seeded from (seed, first_chain + c)
    std::int64_t first_segment = 0;  // boundaries already passed (a resumed run)
    std::vector<ChainState> resume;  // states to continue from (empty: fresh from the seed)
    struct Boundary {
        std::int64_t segment = 0;  // boundaries passed, this one included
        bool finished = false;     // every chain here finished (budget, time, cancel)
        bool stopping = false;     // this process's time budget ran out or it was cancelled
    };
    // Returns false to end the search (every chain stops where it is).
    std::function<bool(const Boundary&, std::vector<ChainState>& states)> at_boundary;
};

struct SearchLogRow {
    double seconds = 0.0;
    std::int64_t evaluations = 0;  // all chains
    double best_objective = 0.0;
};

// Why a search stopped: one name table (search_termination_name) and a sentence each.
enum class SearchTermination { kTimeBudget, kEvaluationBudget, kInterrupted };
const std::vector<std::pair<SearchTermination, std::string>>& search_termination_names();
std::string search_termination_name(SearchTermination t);  // "time budget", ...
std::string search_termination_message(SearchTermination t);

// The best objective over all chains after every chain made `evaluations_per_chain`
// evaluations (or all it made, if fewer): sampled at fixed evaluation counts (1, 2, 3, .., then
// growing by ~19 % a step), so with an evaluation budget it is identical run to run.
struct SearchCheckpoint {
    std::int64_t evaluations_per_chain = 0;
    std::int64_t evaluations = 0;  // all chains
    double best_objective = 0.0;
};

struct SearchSummary {
    std::vector<Candidate> ranked;              // best first, distinct patterns
    std::vector<SearchLogRow> log;              // wall-clock samples (timings: not reproducible)
    std::vector<SearchCheckpoint> checkpoints;  // by evaluation count (reproducible)
    std::vector<std::int64_t> evaluations_per_chain;
    std::vector<ChainState> chain_states;  // each chain's final state (a copyable value)
    // With a pinhole-count range: the best pattern at each K any chain evaluated, ascending K
    // (objective and terms as in `ranked`). Empty otherwise.
    std::vector<Candidate> best_per_holes;
    std::int64_t evaluations = 0;
    double seconds = 0.0;
    SearchTermination termination = SearchTermination::kTimeBudget;
};

// Progress reported about every log_interval_s from the calling thread.
using SearchProgress = std::function<void(const SearchLogRow& row, double budget_fraction)>;

// Runs the search. `sample` draws a valid random pattern (the random family with the wanted n,
// K, spacing and keep-out cells), used by the random strategy and for annealing starts; annealing
// moves keep the spacing rule and avoid options.keep_out, and keep K unless a pinhole-count
// range is set (then K stays inside it; the sampler must draw K inside it too).
// `cancel` (may be null) stops all chains cleanly; the best so far is returned.
SearchSummary run_search(const SearchObjective& objective, const SearchOptions& options,
                         const std::function<Pattern(std::mt19937_64& rng)>& sample,
                         const std::atomic<bool>* cancel = nullptr,
                         const SearchProgress& progress = {},
                         const SearchSegments* segments = nullptr);

// The ranked candidates, evaluation counts and reproducible checkpoints of a set of chain states
// (what run_search returns for its chains; for chains of several processes gathered in one).
// Termination: interrupted when `cancelled`, else evaluation budget when every chain made it.
SearchSummary summarize_chains(const SearchObjective& objective, const SearchOptions& options,
                               std::vector<ChainState> states, bool cancelled);

}  // namespace pinmask
