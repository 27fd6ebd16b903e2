#include <doctest/doctest.h>

#include <algorithm>
#include <mutex>
#include <random>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "design/pattern/pattern.hpp"
#include "optimize/search/pattern_state.hpp"
#include "optimize/search/search.hpp"
#include "tests/optimize/search/sidelobe_fixture.hpp"

using namespace pinmask;
using pinmask::test::sample_pattern;
using pinmask::test::SidelobeObjective;

namespace {

SearchSummary run(SearchStrategy strategy, int threads, std::uint64_t seed,
                  const std::vector<Cell>& keep_out = {}) {
    SearchOptions o;
    o.strategy = strategy;
    o.threads = threads;
    o.seed = seed;
    o.time_budget_s = 0.0;
    o.max_evaluations = 3000;
    o.anneal_restart_moves = 1000;
    o.top = 4;
    o.keep_out = keep_out;
    const SidelobeObjective objective;
    return run_search(objective, o, [&](std::mt19937_64& rng) {
        return sample_pattern(rng, 16, 20, 2.0, keep_out);
    });
}

}  // namespace

TEST_CASE("same seed and thread count give identical results with an evaluation budget") {
    for (auto strategy : {SearchStrategy::kRandom, SearchStrategy::kAnneal}) {
        const auto a = run(strategy, 2, 11), b = run(strategy, 2, 11);
        REQUIRE(a.ranked.size() == b.ranked.size());
        for (std::size_t i = 0; i < a.ranked.size(); ++i) {
            CHECK(a.ranked[i].objective == b.ranked[i].objective);
            CHECK(sorted_pinholes(a.ranked[i].pattern) == sorted_pinholes(b.ranked[i].pattern));
        }
        CHECK(a.evaluations == 6000);
        CHECK(a.termination == SearchTermination::kEvaluationBudget);
        // The evaluation-count log is reproducible (the wall-clock log is not).
        REQUIRE(a.checkpoints.size() == b.checkpoints.size());
        REQUIRE(!a.checkpoints.empty());
        for (std::size_t i = 0; i < a.checkpoints.size(); ++i) {
            CHECK(a.checkpoints[i].evaluations == b.checkpoints[i].evaluations);
            CHECK(a.checkpoints[i].best_objective == b.checkpoints[i].best_objective);
        }
        CHECK(a.checkpoints.front().evaluations_per_chain == 1);
        // Chain states are plain values: the same run gives equal generators and counters.
        REQUIRE(a.chain_states.size() == 2);
        for (std::size_t c = 0; c < 2; ++c) {
            CHECK(a.chain_states[c].rng == b.chain_states[c].rng);
            CHECK(a.chain_states[c].evaluations == 3000);
            CHECK(a.chain_states[c].checkpoints == b.chain_states[c].checkpoints);
            const ChainState copy = a.chain_states[c];
            CHECK(copy.top.items().size() == a.chain_states[c].top.items().size());
        }
        CHECK(a.checkpoints.back().best_objective == a.ranked.front().objective);
    }
}

TEST_CASE("every candidate respects K, the spacing rule and keep-out cells; ranking is sorted") {
    std::vector<Cell> border;
    for (int i = 0; i < 16; ++i) border.push_back({0, i});
    const auto s = run(SearchStrategy::kAnneal, 2, 5, border);
    REQUIRE(s.ranked.size() == 4);
    for (std::size_t i = 0; i < s.ranked.size(); ++i) {
        const Pattern& p = s.ranked[i].pattern;
        CHECK(p.pinholes.size() == 20);
        CHECK(spacing_violations(p).empty());
        for (const Cell& c : p.pinholes) CHECK(c.row != 0);
        if (i > 0) CHECK(s.ranked[i - 1].objective <= s.ranked[i].objective);
        CHECK(s.ranked[i].terms.count("max_sidelobe") == 1);
    }
}

TEST_CASE("annealing beats random sampling on the same evaluation budget") {
    const auto random = run(SearchStrategy::kRandom, 1, 3);
    const auto anneal = run(SearchStrategy::kAnneal, 1, 3);
    CHECK(anneal.ranked.front().objective <= random.ranked.front().objective);
}

TEST_CASE("cancellation stops the chains and keeps the best so far") {
    std::atomic<bool> cancel{true};
    SearchOptions o;
    o.time_budget_s = 60.0;
    const SidelobeObjective objective;
    const auto s = run_search(
        objective, o, [](std::mt19937_64& rng) { return sample_pattern(rng, 16, 20, 2.0, {}); },
        &cancel);
    CHECK(s.termination == SearchTermination::kInterrupted);
}

TEST_CASE("options are validated") {
    SearchOptions o;
    o.threads = 0;
    CHECK_THROWS(o.validate());
    o = {};
    o.time_budget_s = 0.0;
    o.max_evaluations = 0;
    CHECK_THROWS(o.validate());
}

TEST_CASE("a pinhole-count range: K moves inside it, best pattern per K, reproducible") {
    SearchOptions o;
    o.strategy = SearchStrategy::kAnneal;
    o.threads = 2;
    o.seed = 5;
    o.time_budget_s = 0.0;
    o.max_evaluations = 4000;
    o.anneal_restart_moves = 1000;
    o.top = 3;
    o.min_holes = 8;
    o.max_holes = 24;
    o.resize_probability = 0.4;
    const SidelobeObjective objective;
    const auto sample = [&](std::mt19937_64& rng) {
        const int k = std::uniform_int_distribution<int>(o.min_holes, o.max_holes)(rng);
        return sample_pattern(rng, 16, k, 2.0, {});
    };
    const SearchSummary a = run_search(objective, o, sample), b = run_search(objective, o, sample);
    REQUIRE(a.best_per_holes.size() > 5);
    REQUIRE(a.best_per_holes.size() == b.best_per_holes.size());
    int previous = 0;
    for (std::size_t i = 0; i < a.best_per_holes.size(); ++i) {
        const Candidate& c = a.best_per_holes[i];
        const int k = static_cast<int>(c.pattern.pinholes.size());
        CHECK(k >= o.min_holes);
        CHECK(k <= o.max_holes);
        CHECK(k > previous);
        previous = k;
        CHECK(spacing_violations(c.pattern).empty());
        // The recorded objective is the objective of the recorded pattern (incremental state
        // after add/remove moves equals a fresh one).
        CHECK(c.objective == doctest::Approx(objective.evaluate(PatternState(c.pattern))));
        CHECK(sorted_pinholes(c.pattern) == sorted_pinholes(b.best_per_holes[i].pattern));
    }
    // The overall best is the best of the per-K bests.
    const double overall = a.ranked.front().objective;
    double best_of_k = INFINITY;
    for (const Candidate& c : a.best_per_holes) best_of_k = std::min(best_of_k, c.objective);
    CHECK(best_of_k == overall);
    // Without a range nothing per K is kept.
    CHECK(run(SearchStrategy::kAnneal, 1, 3).best_per_holes.empty());
    // A bad range is refused naming the field.
    o.min_holes = 9;
    o.max_holes = 8;
    CHECK_THROWS_AS(run_search(objective, o, sample), InvalidInput);
}

// SearchOptions::on_improvement (what `pinmask search` keeps on disk as best-so-far.mask.json):
// it sees every improvement of every chain, its last call is the run's best, the pattern it is
// handed has the objective it is told (evaluated again here), and it changes nothing in the run.
TEST_CASE("on_improvement watches every chain's improvements without changing the search") {
    for (auto strategy : {SearchStrategy::kRandom, SearchStrategy::kAnneal}) {
        const SearchSummary plain = run(strategy, 2, 7);
        SearchOptions o;
        o.strategy = strategy;
        o.threads = 2;
        o.seed = 7;
        o.time_budget_s = 0.0;
        o.max_evaluations = 3000;
        o.anneal_restart_moves = 1000;
        o.top = 4;
        std::mutex mutex;
        std::vector<std::pair<Pattern, double>> seen;
        o.on_improvement = [&](const Pattern& p, double objective) {
            const std::lock_guard<std::mutex> lock(mutex);
            seen.emplace_back(p, objective);
        };
        const SidelobeObjective objective;
        const SearchSummary watched = run_search(objective, o, [&](std::mt19937_64& rng) {
            return sample_pattern(rng, 16, 20, 2.0, {});
        });
        REQUIRE(watched.ranked.size() == plain.ranked.size());
        for (std::size_t i = 0; i < plain.ranked.size(); ++i) {
            CHECK(watched.ranked[i].objective == plain.ranked[i].objective);
            CHECK(sorted_pinholes(watched.ranked[i].pattern) ==
                  sorted_pinholes(plain.ranked[i].pattern));
        }
        REQUIRE(!seen.empty());
        double best = INFINITY;
        for (const auto& [p, value] : seen) {
            CHECK(value == doctest::Approx(objective.evaluate(PatternState(p))));
            best = std::min(best, value);
        }
        CHECK(best == plain.ranked.front().objective);
        // At least one call per chain (its first evaluation), at most one per evaluation.
        CHECK(seen.size() >= 2);
        CHECK(seen.size() <= 6000);
    }
}
