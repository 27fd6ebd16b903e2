#include "optimize/search/search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// SplitMix64: decorrelated per-chain seeds from (seed, chain).
std::uint64_t chain_seed(std::uint64_t seed, int chain) {
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(chain + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

// The evaluation counts at which chains record their best: 1, 2, .., 16, then ~19 % steps.
std::int64_t next_checkpoint(std::int64_t e) {
    return std::max(e + 1, static_cast<std::int64_t>(std::ceil(static_cast<double>(e) * 1.19)));
}

// A resumed chain state (a checkpoint file, or a message from another rank) is an input: it is
// checked against this run before any chain continues from it. Its patterns must be patterns of
// this search (the grid, tiling, spacing and pinhole count a fresh draw has), its counts within
// the run's budget, its log ordered and within its counts, and every objective it claims must be
// what the objective gives its pattern now: a state claiming 1e9 evaluations or an objective no
// pattern reaches is refused, not copied into the summary.
void check_resumed_state(const ChainState& s, std::size_t chain, const SearchOptions& o,
                         const SearchObjective& objective, const Pattern& reference) {
    const std::string where = "resume: chain " + std::to_string(chain);
    const auto refuse = [&](const std::string& what) { throw InvalidInput(where + ": " + what); };
    const std::int64_t budget =
        o.max_evaluations > 0 ? o.max_evaluations : SearchOptions::kMaxEvaluations;
    if (s.evaluations < 0 || s.evaluations > budget) {
        refuse("claims " + std::to_string(s.evaluations) + " evaluations; this run's budget is " +
               std::to_string(budget) + " per chain");
    }
    std::int64_t previous = 0;
    double previous_best = INFINITY;
    for (const auto& [e, best] : s.checkpoints) {
        if (e <= previous || e > s.evaluations) {
            refuse("its log must count evaluations upwards within the chain's " +
                   std::to_string(s.evaluations) + " (entry at " + std::to_string(e) + ")");
        }
        if (best > previous_best) {
            refuse("its log's best objective rises at " + std::to_string(e) +
                   " evaluations (a best so far never gets worse)");
        }
        previous = e;
        previous_best = best;
    }
    if (s.best_objective > previous_best) {
        refuse("its best objective is worse than its log's last entry");
    }
    // The log is the chain's own: an entry at each of 1, 2, .., 16 and then ~19 % steps up to
    // its evaluations (and one at its evaluations when it finished), the next step its
    // next_log_at.
    std::int64_t step = 1;
    for (std::size_t k = 0; k < s.checkpoints.size(); ++k) {
        const std::int64_t e = s.checkpoints[k].first;
        if (e == step) {
            step = next_checkpoint(step);
        } else if (k + 1 != s.checkpoints.size() || e != s.evaluations) {
            refuse("its log has an entry at " + std::to_string(e) + " evaluations where the " +
                   "chain logs at " + std::to_string(step));
        }
    }
    if (step <= s.evaluations)
        refuse("its log lacks the entry at " + std::to_string(step) + " evaluations");
    if (s.next_checkpoint != step) {
        refuse("its next log entry is at " + std::to_string(s.next_checkpoint) +
               " evaluations; after " + std::to_string(s.evaluations) + " the chain logs at " +
               std::to_string(step));
    }
    const auto check_pattern = [&](const Pattern& p, const std::string& what) {
        const bool holes_ok = o.holes_range()
                                  ? static_cast<int>(p.pinholes.size()) >= o.min_holes &&
                                        static_cast<int>(p.pinholes.size()) <= o.max_holes
                                  : p.pinholes.size() == reference.pinholes.size();
        if (p.n != reference.n || p.tiles_rows != reference.tiles_rows ||
            p.tiles_cols != reference.tiles_cols ||
            p.min_spacing_cells != reference.min_spacing_cells || !holes_ok) {
            refuse(what + " is not a pattern of this search (grid " + std::to_string(p.n) + ", " +
                   std::to_string(p.pinholes.size()) + " pinholes; this run: grid " +
                   std::to_string(reference.n) + ")");
        }
    };
    // Objectives are recomputed, so equal up to the FFT's rounding; a tampered value is not.
    const auto check_objective = [&](const Pattern& p, double claimed, const std::string& what) {
        check_pattern(p, what);
        const double actual = objective.evaluate(PatternState(p));
        if (!(std::abs(claimed - actual) <= 1e-6 * std::max(1.0, std::abs(actual)))) {
            refuse(what + " claims the objective " + std::to_string(claimed) +
                   "; its pattern's objective is " + std::to_string(actual));
        }
    };
    const auto& items = s.top.items();
    for (std::size_t i = 0; i < items.size(); ++i)
        check_objective(items[i].pattern, items[i].objective, "top candidate " + std::to_string(i));
    const double best_listed = items.empty() ? INFINITY : items.front().objective;
    if (s.best_objective != best_listed) {
        refuse("its best objective " + std::to_string(s.best_objective) +
               " is not its best candidate's (" + std::to_string(best_listed) + ")");
    }
    if (s.evaluations == 0 && !items.empty()) refuse("lists candidates before any evaluation");
    for (const auto& [k, best] : s.best_per_holes) {
        for (const auto& item : best.items())
            check_objective(item.pattern, item.objective,
                            "the best pattern of " + std::to_string(k) + " pinholes");
        for (const auto& item : best.items())
            if (static_cast<int>(item.pattern.pinholes.size()) != k)
                refuse("its best pattern of " + std::to_string(k) + " pinholes has " +
                       std::to_string(item.pattern.pinholes.size()));
    }
    if (s.start) check_pattern(*s.start, "its next start");
}

struct ChainShared {
    std::atomic<std::int64_t> evaluations{0};
    std::atomic<double> best{INFINITY};
};

class Chain {
  public:
    Chain(const SearchOptions& o, const SearchObjective& obj,
          const std::function<Pattern(std::mt19937_64&)>& sample, int index,
          const std::atomic<bool>* cancel, const std::atomic<bool>* time_up, ChainShared* shared)
        : o_(o),
          obj_(obj),
          sample_(sample),
          cancel_(cancel),
          time_up_(time_up),
          shared_(shared),
          st_{std::mt19937_64(chain_seed(o.seed, index)),
              0,
              INFINITY,
              1,
              {},
              TopCandidates(o.top),
              {},
              {}} {
        for (const Cell& c : o.keep_out) keep_out_.push_back(c);
    }

    // Runs until the chain finishes or, at a restart boundary, has made at least `pause_at`
    // evaluations (0: no pause). Returns true when finished.
    bool run(std::int64_t pause_at = 0) {
        const auto pausing = [&] { return pause_at > 0 && st_.evaluations >= pause_at; };
        if (o_.strategy == SearchStrategy::kRandom) {
            while (!should_stop() && !pausing()) {
                const PatternState s(sample_(st_.rng));
                record(s, obj_.evaluate(s));
            }
        } else {
            while (!should_stop() && !pausing()) anneal_once();
        }
        if (!should_stop()) return false;
        finish();
        return true;
    }
    // Records the final (evaluations, best) entry of the chain's log once.
    void finish() {
        if (st_.evaluations > 0 &&
            (st_.checkpoints.empty() || st_.checkpoints.back().first != st_.evaluations))
            st_.checkpoints.push_back({st_.evaluations, st_.best_objective});
    }
    ChainState& mutable_state() { return st_; }
    const TopCandidates& top() const { return st_.top; }
    const ChainState& state() const { return st_; }
    std::int64_t evaluations() const { return st_.evaluations; }
    // (evaluations, best objective so far) at the checkpoint evaluation counts.
    const std::vector<std::pair<std::int64_t, double>>& checkpoints() const {
        return st_.checkpoints;
    }

  private:
    bool should_stop() const {
        if (o_.max_evaluations > 0 && st_.evaluations >= o_.max_evaluations) return true;
        if (cancel_ && cancel_->load(std::memory_order_relaxed)) return true;
        return time_up_->load(std::memory_order_relaxed);
    }

    void record(const PatternState& s, double value) {
        ++st_.evaluations;
        const bool improved = value < st_.best_objective;
        st_.best_objective = std::min(st_.best_objective, value);
        if (st_.evaluations == st_.next_checkpoint) {
            st_.checkpoints.push_back({st_.evaluations, st_.best_objective});
            st_.next_checkpoint = next_checkpoint(st_.evaluations);
        }
        shared_->evaluations.store(st_.evaluations, std::memory_order_relaxed);
        if (value < st_.top.worst()) st_.top.offer(s.pattern(), value);
        if (o_.holes_range()) {
            TopCandidates& best = st_.best_per_holes.try_emplace(s.holes(), 1).first->second;
            if (value < best.worst()) best.offer(s.pattern(), value);
        }
        if (value < shared_->best.load(std::memory_order_relaxed)) {
            shared_->best.store(value, std::memory_order_relaxed);
        }
        if (improved && o_.on_improvement) o_.on_improvement(s.pattern(), value);
    }

    bool blocked(Cell c) const {
        return std::find(keep_out_.begin(), keep_out_.end(), c) != keep_out_.end();
    }

    // Proposes a legal move (j, to); false when none was found in a bounded number of draws.
    bool propose(const PatternState& s, int& j, Cell& to) {
        std::uniform_int_distribution<int> hole(0, s.holes() - 1), cell(0, s.n() - 1);
        for (int attempt = 0; attempt < 64; ++attempt) {
            j = hole(st_.rng);
            to = {cell(st_.rng), cell(st_.rng)};
            if (!blocked(to) && s.is_legal_move(j, to)) return true;
        }
        return false;
    }

    // An empty cell where a pinhole may be added, or false after a bounded number of draws.
    bool propose_add(const PatternState& s, Cell& at) {
        std::uniform_int_distribution<int> cell(0, s.n() - 1);
        for (int attempt = 0; attempt < 64; ++attempt) {
            at = {cell(st_.rng), cell(st_.rng)};
            if (!blocked(at) && s.can_add(at)) return true;
        }
        return false;
    }

    // One annealing move: a swap, or with a pinhole-count range an add or a remove. Applies it
    // and returns the undo; false when no legal move was found.
    struct Undo {
        enum { kMove, kAdded, kRemoved } kind = kMove;
        int j = 0;
        Cell cell{};
        void apply(PatternState& s) const {
            if (kind == kMove) s.move(j, cell);
            if (kind == kAdded) s.remove(s.holes() - 1);
            if (kind == kRemoved) s.add(cell);
        }
    };
    bool step(PatternState& s, std::uniform_real_distribution<double>& uniform, Undo& undo) {
        if (o_.holes_range()) {
            const double u = uniform(st_.rng);
            Cell at;
            if (u < 0.5 * o_.resize_probability && s.holes() < o_.max_holes && propose_add(s, at)) {
                s.add(at);
                undo = {Undo::kAdded, 0, {}};
                return true;
            }
            if (u >= 0.5 * o_.resize_probability && u < o_.resize_probability &&
                s.holes() > o_.min_holes) {
                std::uniform_int_distribution<int> hole(0, s.holes() - 1);
                const int j = hole(st_.rng);
                undo = {Undo::kRemoved, 0, s.pattern().pinholes[static_cast<std::size_t>(j)]};
                s.remove(j);
                return true;
            }
        }
        int j;
        Cell to;
        if (!propose(s, j, to)) return false;
        undo = {Undo::kMove, j, s.pattern().pinholes[static_cast<std::size_t>(j)]};
        s.move(j, to);
        return true;
    }

    // One annealing restart: a fresh random start, a geometric temperature schedule over a fixed
    // number of moves (independent of the budget, so runs are reproducible by evaluation count).
    void anneal_once() {
        PatternState s(st_.start ? *st_.start : sample_(st_.rng));
        st_.start.reset();
        double current = obj_.evaluate(s);
        record(s, current);
        // Temperature scale: mean |change| of a few trial moves (applied and reverted).
        double sum = 0.0;
        int count = 0;
        for (int t = 0; t < 32 && !should_stop(); ++t) {
            int j;
            Cell to;
            if (!propose(s, j, to)) break;
            const Cell from = s.pattern().pinholes[static_cast<std::size_t>(j)];
            s.move(j, to);
            const double v = obj_.evaluate(s);
            record(s, v);
            sum += std::fabs(v - current);
            ++count;
            s.move(j, from);
        }
        const double t0 = count > 0 && sum > 0.0 ? sum / count : 1.0;
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        const std::int64_t moves = o_.anneal_restart_moves;
        for (std::int64_t m = 0; m < moves && !should_stop(); ++m) {
            if ((m & 4095) == 4095) s.recompute();  // bound accumulated round-off in P^
            Undo undo;
            if (!step(s, uniform, undo)) return;  // stuck: restart
            const double temperature =
                t0 * std::pow(o_.anneal_final_temperature_ratio, static_cast<double>(m) / moves);
            const double v = obj_.evaluate(s);
            record(s, v);
            if (v <= current || uniform(st_.rng) < std::exp((current - v) / temperature)) {
                current = v;
            } else {
                undo.apply(s);
            }
        }
    }

    const SearchOptions& o_;
    const SearchObjective& obj_;
    const std::function<Pattern(std::mt19937_64&)>& sample_;
    const std::atomic<bool>* cancel_;
    const std::atomic<bool>* time_up_;
    ChainShared* shared_;
    std::vector<Cell> keep_out_;
    ChainState st_;
};

}  // namespace

const std::vector<std::pair<SearchTermination, std::string>>& search_termination_names() {
    static const std::vector<std::pair<SearchTermination, std::string>> kNames{
        {SearchTermination::kTimeBudget, "time budget"},
        {SearchTermination::kEvaluationBudget, "evaluation budget"},
        {SearchTermination::kInterrupted, "interrupted"}};
    return kNames;
}

std::string search_termination_name(SearchTermination t) {
    for (const auto& [k, name] : search_termination_names())
        if (k == t) return name;
    return "unknown";
}

std::string search_termination_message(SearchTermination t) {
    switch (t) {
        case SearchTermination::kTimeBudget:
            return "the time budget ran out";
        case SearchTermination::kEvaluationBudget:
            return "every chain made its evaluation budget";
        case SearchTermination::kInterrupted:
            return "interrupted (signal or cancel); the best so far is kept";
    }
    return "unknown";
}

void SearchOptions::validate() const {
    if (threads < 1 || threads > 1024) {
        throw invalid_field(field_ref("threads"), std::to_string(threads),
                            "must be between 1 and 1024");
    }
    // The same bound as the process's time budget (core/limits/resource_limits): a longer search
    // cannot be told from a hang.
    if (!(time_budget_s >= 0.0) || !(time_budget_s <= kMaxTimeLimitS)) {
        throw invalid_field(field_ref("time_budget_s"), std::to_string(time_budget_s),
                            "must be between 0 and 1e7 s (116 days)");
    }
    // 1e9 evaluations a chain is more than a day at the fastest rate `bench search` measures; a
    // longer search is a time budget (it always ends, with the best so far).
    if (max_evaluations < 0 || max_evaluations > kMaxEvaluations) {
        throw invalid_field(field_ref("max_evaluations"), std::to_string(max_evaluations),
                            "must be 0 (no evaluation budget) to 1e9 evaluations per chain (over "
                            "a day of search): a longer search is a time budget");
    }
    if (time_budget_s == 0.0 && max_evaluations == 0) {
        throw InvalidInput("search needs a budget: a time budget > 0 or an evaluation budget > 0");
    }
    if (top < 1 || top > kMaxTop) {
        throw invalid_field(field_ref("top"), std::to_string(top), "must be between 1 and 1000");
    }
    if (anneal_restart_moves < 1) {
        throw invalid_field("anneal_restart_moves", std::to_string(anneal_restart_moves),
                            "must be >= 1");
    }
    if (!(anneal_final_temperature_ratio > 0.0 && anneal_final_temperature_ratio <= 1.0)) {
        throw invalid_field("anneal_final_temperature_ratio",
                            std::to_string(anneal_final_temperature_ratio), "must be in (0, 1]");
    }
    if (min_holes != 0 || max_holes != 0) {
        if (min_holes < 1 || max_holes < min_holes) {
            throw invalid_field("holes range",
                                std::to_string(min_holes) + ".." + std::to_string(max_holes),
                                "must satisfy 1 <= min_holes <= max_holes");
        }
    }
    if (!(resize_probability >= 0.0 && resize_probability <= 1.0)) {
        throw invalid_field("resize_probability", std::to_string(resize_probability),
                            "must be in [0, 1]");
    }
    if (!(log_interval_s > 0.0)) {
        throw invalid_field("log_interval_s", std::to_string(log_interval_s), "must be > 0");
    }
}

SearchSummary run_search(const SearchObjective& objective, const SearchOptions& options,
                         const std::function<Pattern(std::mt19937_64&)>& sample,
                         const std::atomic<bool>* cancel, const SearchProgress& progress,
                         const SearchSegments* segments) {
    options.validate();
    const bool segmented = segments != nullptr && segments->at_boundary;
    if (segmented && segments->every < 1) {
        throw invalid_field("segments.every", std::to_string(segments->every), "must be >= 1");
    }
    const auto t0 = Clock::now();
    std::atomic<bool> time_up{false};
    std::vector<ChainShared> shared(static_cast<std::size_t>(options.threads));
    std::vector<std::unique_ptr<Chain>> chains;
    const int first_chain = segments ? segments->first_chain : 0;
    for (int c = 0; c < options.threads; ++c) {
        chains.push_back(std::make_unique<Chain>(options, objective, sample, first_chain + c,
                                                 cancel, &time_up,
                                                 &shared[static_cast<std::size_t>(c)]));
    }
    if (segments && !segments->resume.empty()) {
        if (segments->resume.size() != chains.size()) {
            throw invalid_field(
                "resume", std::to_string(segments->resume.size()) + " chains",
                "must be one state per chain (" + std::to_string(chains.size()) + ")");
        }
        // What a fresh draw looks like: the grid, tiling, spacing and pinhole count of this run.
        std::mt19937_64 probe(options.seed);
        const Pattern reference = sample(probe);
        for (std::size_t c = 0; c < chains.size(); ++c)
            check_resumed_state(segments->resume[c], c, options, objective, reference);
        for (std::size_t c = 0; c < chains.size(); ++c) {
            chains[c]->mutable_state() = segments->resume[c];
            shared[c].evaluations = segments->resume[c].evaluations;
            shared[c].best = segments->resume[c].best_objective;
        }
    }
    SearchSummary summary;
    auto sample_log = [&] {
        SearchLogRow row;
        row.seconds = seconds_since(t0);
        row.best_objective = INFINITY;
        for (const auto& s : shared) {
            row.evaluations += s.evaluations.load(std::memory_order_relaxed);
            row.best_objective = std::min(row.best_objective, s.best.load());
        }
        summary.log.push_back(row);
        return row;
    };
    double next_log = 0.0;
    std::int64_t segment = segments ? segments->first_segment : 0;
    std::vector<char> finished(chains.size(), 0);
    for (;;) {
        const std::int64_t pause_at = segmented ? (segment + 1) * segments->every : 0;
        std::vector<std::exception_ptr> errors(chains.size());
        std::mutex mutex;
        std::condition_variable cv;
        int running = options.threads;
        std::vector<std::thread> workers;
        workers.reserve(chains.size());
        try {
            for (std::size_t c = 0; c < chains.size(); ++c) {
                workers.emplace_back([&, c] {
                    try {
                        finished[c] = chains[c]->run(pause_at) ? 1 : 0;
                    } catch (...) {
                        errors[c] = std::current_exception();
                        time_up = true;  // stop the others too
                    }
                    const std::lock_guard<std::mutex> lock(mutex);
                    --running;
                    cv.notify_all();
                });
            }
        } catch (const std::system_error& e) {
            // The system refused a thread (a process or memory limit): the chains started are
            // stopped and joined (a joinable thread destroyed would abort the process), and the
            // request is refused.
            time_up = true;
            for (std::thread& w : workers) w.join();
            throw ResourceLimit(field_ref("threads") + " = " + std::to_string(options.threads) +
                                ": the system could not start chain " +
                                std::to_string(workers.size() + 1) + "'s thread (" + e.what() +
                                "); use fewer threads");
        }
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex);
                if (cv.wait_for(lock, std::chrono::milliseconds(5), [&] { return running == 0; }))
                    break;
            }
            const double now = seconds_since(t0);
            if (options.time_budget_s > 0.0 && now >= options.time_budget_s) time_up = true;
            if (now >= next_log) {
                const SearchLogRow row = sample_log();
                double fraction = 0.0;
                if (options.time_budget_s > 0.0) fraction = now / options.time_budget_s;
                if (options.max_evaluations > 0) {
                    fraction = std::max(
                        fraction,
                        static_cast<double>(row.evaluations) /
                            (static_cast<double>(options.max_evaluations) * options.threads));
                }
                if (progress) progress(row, std::min(fraction, 1.0));
                next_log = now + options.log_interval_s;
            }
        }
        for (auto& w : workers) w.join();
        for (const auto& e : errors) {
            if (e) std::rethrow_exception(e);
        }
        if (!segmented) break;
        ++segment;
        SearchSegments::Boundary b;
        b.segment = segment;
        b.finished = std::all_of(finished.begin(), finished.end(), [](char f) { return f != 0; });
        b.stopping = time_up.load() || (cancel && cancel->load());
        std::vector<ChainState> states;
        for (const auto& chain : chains) states.push_back(chain->state());
        const bool go_on = segments->at_boundary(b, states);
        for (std::size_t c = 0; c < chains.size(); ++c)
            chains[c]->mutable_state() = std::move(states[c]);
        if (!go_on) break;
    }
    for (auto& chain : chains) chain->finish();
    sample_log();
    std::vector<ChainState> states;
    for (const auto& chain : chains) states.push_back(chain->state());
    SearchSummary merged =
        summarize_chains(objective, options, std::move(states), cancel && cancel->load());
    merged.log = std::move(summary.log);
    merged.seconds = seconds_since(t0);
    return merged;
}

SearchSummary summarize_chains(const SearchObjective& objective, const SearchOptions& options,
                               std::vector<ChainState> states, bool cancelled) {
    SearchSummary summary;
    std::vector<TopCandidates::Item> all;
    for (const ChainState& st : states) {
        summary.evaluations_per_chain.push_back(st.evaluations);
        summary.evaluations += st.evaluations;
        for (const auto& item : st.top.items()) all.push_back(item);
    }
    std::sort(all.begin(), all.end(), TopCandidates::less);
    for (const auto& item : all) {
        if (static_cast<int>(summary.ranked.size()) == options.top) break;
        const bool seen =
            std::any_of(summary.ranked.begin(), summary.ranked.end(),
                        [&](const Candidate& c) { return sorted_pinholes(c.pattern) == item.key; });
        if (seen) continue;
        Candidate c;
        c.pattern = item.pattern;
        c.objective = item.objective;
        c.terms = objective.terms(PatternState(item.pattern));
        summary.ranked.push_back(std::move(c));
    }
    if (options.holes_range()) {
        std::map<int, TopCandidates::Item> best;
        for (const ChainState& st : states) {
            for (const auto& [k, top] : st.best_per_holes) {
                if (top.items().empty()) continue;
                const TopCandidates::Item& item = top.items().front();
                const auto it = best.find(k);
                if (it == best.end() || TopCandidates::less(item, it->second))
                    best.insert_or_assign(k, item);
            }
        }
        for (const auto& [k, item] : best) {
            Candidate c;
            c.pattern = item.pattern;
            c.objective = item.objective;
            c.terms = objective.terms(PatternState(item.pattern));
            summary.best_per_holes.push_back(std::move(c));
        }
    }
    // Checkpoints merged over chains: every chain records at the same evaluation counts.
    std::vector<std::int64_t> counts;
    for (const ChainState& st : states)
        for (const auto& [e, best] : st.checkpoints) counts.push_back(e);
    std::sort(counts.begin(), counts.end());
    counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
    // One pass: each chain's log is ordered, so a cursor per chain moves forward with e and
    // its best so far is kept (a rescan of every log for each count was quadratic).
    std::vector<std::size_t> cursor(states.size(), 0);
    std::vector<double> best_so_far(states.size(), INFINITY);
    for (const std::int64_t e : counts) {
        SearchCheckpoint cp;
        cp.evaluations_per_chain = e;
        cp.best_objective = INFINITY;
        for (std::size_t c = 0; c < states.size(); ++c) {
            const ChainState& st = states[c];
            cp.evaluations += std::min(e, st.evaluations);
            while (cursor[c] < st.checkpoints.size() && st.checkpoints[cursor[c]].first <= e) {
                best_so_far[c] = std::min(best_so_far[c], st.checkpoints[cursor[c]].second);
                ++cursor[c];
            }
            cp.best_objective = std::min(cp.best_objective, best_so_far[c]);
        }
        summary.checkpoints.push_back(cp);
    }
    if (cancelled) {
        summary.termination = SearchTermination::kInterrupted;
    } else if (options.max_evaluations > 0 &&
               std::all_of(summary.evaluations_per_chain.begin(),
                           summary.evaluations_per_chain.end(),
                           [&](std::int64_t e) { return e >= options.max_evaluations; })) {
        summary.termination = SearchTermination::kEvaluationBudget;
    } else {
        summary.termination = SearchTermination::kTimeBudget;
    }
    summary.chain_states = std::move(states);
    return summary;
}

}  // namespace pinmask
