// Segmented search, resume and the island model on one process: pausing at restart
// boundaries changes nothing; a run resumed from states captured at a boundary (directly, through
// the binary codec and through the JSON checkpoint codec) ends equal to the uninterrupted run;
// migration follows its rule (checked against the rule recomputed from the states).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "io/checkpoint.hpp"
#include "optimize/search/chain_codec.hpp"
#include "optimize/search/island_search.hpp"
#include "optimize/search/search.hpp"
#include "tests/optimize/search/sidelobe_fixture.hpp"

using namespace pinmask;
using pinmask::test::SidelobeObjective;

namespace {

// n = 13 with 12 holes has no perfect difference set: chains end apart.
Pattern sample(std::mt19937_64& rng) { return test::sample_pattern(rng, 13, 12, 1.5); }

SearchOptions options(SearchStrategy strategy = SearchStrategy::kAnneal) {
    SearchOptions o;
    o.strategy = strategy;
    o.threads = 2;
    o.seed = 5;
    o.time_budget_s = 0.0;
    o.max_evaluations = 5000;
    o.anneal_restart_moves = 600;
    o.top = 4;
    return o;
}

bool same_state(const ChainState& a, const ChainState& b) {
    bool same = a.rng == b.rng && a.evaluations == b.evaluations &&
                a.best_objective == b.best_objective && a.next_checkpoint == b.next_checkpoint &&
                a.checkpoints == b.checkpoints && a.top.items().size() == b.top.items().size() &&
                a.start.has_value() == b.start.has_value();
    for (std::size_t i = 0; same && i < a.top.items().size(); ++i) {
        same = a.top.items()[i].objective == b.top.items()[i].objective &&
               a.top.items()[i].pattern.pinholes == b.top.items()[i].pattern.pinholes;
    }
    return same && (!a.start || a.start->pinholes == b.start->pinholes);
}

void check_same(const SearchSummary& a, const SearchSummary& b) {
    REQUIRE(a.ranked.size() == b.ranked.size());
    for (std::size_t i = 0; i < a.ranked.size(); ++i) {
        CHECK(a.ranked[i].objective == b.ranked[i].objective);
        CHECK(a.ranked[i].pattern.pinholes == b.ranked[i].pattern.pinholes);
    }
    CHECK(a.evaluations_per_chain == b.evaluations_per_chain);
    REQUIRE(a.checkpoints.size() == b.checkpoints.size());
    for (std::size_t i = 0; i < a.checkpoints.size(); ++i) {
        CHECK(a.checkpoints[i].evaluations == b.checkpoints[i].evaluations);
        CHECK(a.checkpoints[i].best_objective == b.checkpoints[i].best_objective);
    }
    REQUIRE(a.chain_states.size() == b.chain_states.size());
    for (std::size_t c = 0; c < a.chain_states.size(); ++c)
        CHECK(same_state(a.chain_states[c], b.chain_states[c]));
    CHECK(a.termination == b.termination);
}

}  // namespace

TEST_CASE("pausing at restart boundaries changes nothing (anneal and random)") {
    const SidelobeObjective obj;
    for (SearchStrategy strategy : {SearchStrategy::kAnneal, SearchStrategy::kRandom}) {
        const SearchOptions o = options(strategy);
        const SearchSummary plain = run_search(obj, o, sample);
        int boundaries = 0;
        SearchSegments seg;
        seg.every = 700;
        seg.at_boundary = [&](const SearchSegments::Boundary& b, std::vector<ChainState>&) {
            ++boundaries;
            return !b.finished;
        };
        const SearchSummary paused = run_search(obj, o, sample, nullptr, {}, &seg);
        CHECK(boundaries >= 5000 / 700 - 1);
        check_same(plain, paused);
    }
}

TEST_CASE(
    "resumed from a boundary (directly, binary codec, JSON checkpoint) equals the "
    "uninterrupted run") {
    const SidelobeObjective obj;
    const SearchOptions o = options();
    const SearchSummary plain = run_search(obj, o, sample);
    std::vector<ChainState> at3;
    SearchSegments seg;
    seg.every = 1000;
    seg.at_boundary = [&](const SearchSegments::Boundary& b, std::vector<ChainState>& states) {
        if (b.segment == 3) at3 = states;
        return !b.finished;
    };
    run_search(obj, o, sample, nullptr, {}, &seg);
    REQUIRE(at3.size() == 2);
    CHECK(at3[0].evaluations >= 3000);
    CHECK(at3[0].evaluations < o.max_evaluations);

    io::SearchCheckpointFile file;
    file.config = {{"seed", 5}};
    file.segment = 3;
    file.every = 1000;
    file.chains = at3;
    const io::SearchCheckpointFile back = io::parse_checkpoint(io::checkpoint_to_json(file));
    CHECK(back.segment == 3);
    CHECK(back.every == 1000);
    CHECK(io::differing_keys(file.config, back.config).empty());
    const std::vector<ChainState> decoded = decode_chain_states(encode_chain_states(at3));
    for (const std::vector<ChainState>* states :
         {static_cast<const std::vector<ChainState>*>(&at3), &decoded, &back.chains}) {
        for (std::size_t c = 0; c < at3.size(); ++c) CHECK(same_state((*states)[c], at3[c]));
        SearchSegments resume;
        resume.every = 1000;
        resume.first_segment = 3;
        resume.resume = *states;
        resume.at_boundary = [](const SearchSegments::Boundary& b, std::vector<ChainState>&) {
            return !b.finished;
        };
        check_same(plain, run_search(obj, o, sample, nullptr, {}, &resume));
    }
}

// A checkpoint's checksum recomputed after an edit, as a forger would (FNV-1a 64 written out
// here, not the library's): the fields must still be checked one by one.
std::string resealed(std::string text) {
    const std::string key = "\"checksum\": \"";
    const std::size_t at = text.rfind(key) + key.size();
    text.replace(at, 16, "0000000000000000");
    unsigned long long h = 0xcbf29ce484222325ULL;
    for (const unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", h);
    text.replace(at, 16, hex);
    return text;
}

TEST_CASE("checkpoint codec: an edited file is refused by its checksum") {
    io::SearchCheckpointFile file;
    file.segment = 1;
    file.every = 10;
    file.chains.resize(1);
    const std::string good = io::checkpoint_to_json(file);
    CHECK(resealed(good) == good);  // the writer's checksum is the FNV-1a 64 of its zeroed text
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"\"segment\": 1", "\"segment\": 2"},
             {"\"evaluations\": 0", "\"evaluations\": 1"},
             {"\"rng\": \"", "\"rng\": \" "},
             {"\"checksum\": \"", "\"checksum\":\""}}) {
        std::string text = good;
        text.replace(text.find(from), from.size(), to);
        CHECK_THROWS_WITH_AS(io::parse_checkpoint(text),
                             doctest::Contains(to.find("checksum") == std::string::npos
                                                   ? "the checkpoint was changed after it was "
                                                     "written"
                                                   : "checksum"),
                             InvalidInput);
    }
    std::string unsealed = good;
    unsealed.replace(unsealed.rfind("\"checksum\""), 10, "\"checksun\"");
    CHECK_THROWS_WITH_AS(io::parse_checkpoint(unsealed), doctest::Contains("checksun"),
                         InvalidInput);
}

TEST_CASE("checkpoint codec: hostile files are refused naming the key") {
    io::SearchCheckpointFile file;
    file.segment = 1;
    file.every = 10;
    file.chains.resize(1);
    const std::string good = io::checkpoint_to_json(file);
    CHECK_NOTHROW(io::parse_checkpoint(good));
    auto refused = [&](const std::string& from, const std::string& to, const std::string& key) {
        std::string text = good;
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
        if (text.rfind("\"checksum\": \"") != std::string::npos) text = resealed(text);
        try {
            io::parse_checkpoint(text);
            FAIL("accepted: " << to);
        } catch (const InvalidInput& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(key) != std::string::npos);
        }
    };
    refused("\"segment\": 1", "\"segment\": 0", "segment");
    refused("\"segment\": 1", "\"segment\": -4", "segment");
    refused("\"rng\": \"", "\"rng\": \"x", "chains[0].rng");
    refused("\"top_capacity\": 1", "\"top_capacity\": 0", "chains[0].top_capacity");
    refused("\"evaluations\": 0", "\"evaluations\": 1e400", "(root)");
    refused("\"version\": 2", "\"version\": 1", "version 1 checkpoints carry no checksum");
    refused("\"version\": 2", "\"version\": 3", "version");
    // generator states the stream reader would wrap or misread
    const std::string state = [] {
        std::ostringstream s;
        s << std::mt19937_64{};
        return s.str();
    }();
    const std::string first_word = state.substr(0, state.find(' '));
    refused("\"rng\": \"" + first_word, "\"rng\": \"-5", "is not an integer of 0..2^64-1");
    refused("\"rng\": \"" + first_word, "\"rng\": \"18446744073709551616",
            "is not an integer of 0..2^64-1");
    refused(" 312\"", " 312 5\"", "more than 313 numbers");
    refused(" 312\"", " 313\"", "its index 313 is beyond 312");
    refused("\"segment\": 1", "\"segment\": 1, \"segment\": 1", "segment");
    CHECK(io::differing_keys({{"a", 1}, {"b", {{"x", 1}, {"y", 2}}}},
                             {{"b", {{"y", 2}, {"x", 1}}}, {"a", 2}, {"c", 0}}) ==
          std::vector<std::string>{"a", "c"});
}

TEST_CASE("a resumed state is checked against the run: counts, log, patterns, objectives") {
    const SidelobeObjective obj;
    const SearchOptions o = options(SearchStrategy::kRandom);
    std::vector<ChainState> at2;
    SearchSegments seg;
    seg.every = 1000;
    seg.at_boundary = [&](const SearchSegments::Boundary& b, std::vector<ChainState>& states) {
        if (b.segment == 2) at2 = states;
        return !b.finished;
    };
    run_search(obj, o, sample, nullptr, {}, &seg);
    REQUIRE(at2.size() == 2);
    REQUIRE_FALSE(at2[0].top.items().empty());
    REQUIRE(at2[0].checkpoints.size() >= 3);
    const auto resumed = [&](const std::vector<ChainState>& states) {
        SearchSegments r;
        r.every = 1000;
        r.first_segment = 2;
        r.resume = states;
        r.at_boundary = [](const SearchSegments::Boundary& b, std::vector<ChainState>&) {
            return !b.finished;
        };
        return run_search(obj, o, sample, nullptr, {}, &r);
    };
    CHECK_NOTHROW(resumed(at2));  // the states as captured
    const auto refused = [&](const std::function<void(ChainState&)>& edit,
                             const std::string& fragment) {
        std::vector<ChainState> states = at2;
        edit(states[1]);
        CHECK_THROWS_WITH_AS(resumed(states), doctest::Contains(fragment.c_str()), InvalidInput);
    };
    // More evaluations than the run's budget (the file claimed 1e9).
    refused([](ChainState& s) { s.evaluations = 1'000'000'000; }, "claims 1000000000 evaluations");
    // An objective no pattern of this search reaches: the best candidate re-evaluated.
    refused(
        [](ChainState& s) {
            std::vector<std::pair<Pattern, double>> items;
            for (const auto& it : s.top.items()) items.push_back({it.pattern, it.objective});
            items.front().second = -1000.0;
            s.top = TopCandidates(static_cast<int>(s.top.capacity()));
            for (const auto& [pattern, objective] : items) s.top.offer(pattern, objective);
            s.best_objective = -1000.0;
        },
        "claims the objective -1000");
    refused([](ChainState& s) { s.best_objective -= 1.0; }, "is not its best candidate's");
    refused([](ChainState& s) { std::swap(s.checkpoints[1], s.checkpoints[2]); },
            "its log must count evaluations upwards");
    refused(
        [](ChainState& s) {
            s.checkpoints.push_back({s.evaluations + 1, s.best_objective});
        },
        "its log must count evaluations upwards");
    refused([](ChainState& s) { s.checkpoints.back().second = s.checkpoints.front().second + 1; },
            "best objective rises");
    // the log and its next step are the chain's own: 1, 2, .., 16, then ~19 % steps
    refused([](ChainState& s) { s.checkpoints.erase(s.checkpoints.begin() + 1); },
            "its log has an entry at 3 evaluations where the chain logs at 2");
    refused([](ChainState& s) { s.next_checkpoint += 1; }, "its next log entry is at");
    refused([](ChainState& s) { s.checkpoints.pop_back(); }, "its log lacks the entry at");
    refused(
        [](ChainState& s) {
            Pattern p = s.top.items().front().pattern;
            p.n = 17;
            s.start = p;
        },
        "not a pattern of this search");
}

TEST_CASE("checkpoint logs: bounded and ordered when read") {
    io::SearchCheckpointFile file;
    file.segment = 1;
    file.every = 10;
    file.chains.resize(1);
    file.chains[0].evaluations = 5000;
    for (std::int64_t e = 1; e <= 4097; ++e) file.chains[0].checkpoints.push_back({e, 1.0});
    CHECK_THROWS_WITH_AS(io::parse_checkpoint(io::checkpoint_to_json(file)),
                         doctest::Contains("has 4097 entries"), InvalidInput);
    file.chains[0].checkpoints.resize(4096);
    CHECK_NOTHROW(io::parse_checkpoint(io::checkpoint_to_json(file)));
    file.chains[0].checkpoints = {{1, 1.0}, {3, 1.0}, {2, 1.0}};
    CHECK_THROWS_WITH_AS(io::parse_checkpoint(io::checkpoint_to_json(file)),
                         doctest::Contains("chains[0].log[2][0]"), InvalidInput);
    file.chains[0].checkpoints = {{1, 1.0}, {6000, 1.0}};
    CHECK_THROWS_WITH_AS(io::parse_checkpoint(io::checkpoint_to_json(file)),
                         doctest::Contains("at most the chain's evaluations"), InvalidInput);
}

TEST_CASE("island model on one process: chains worse than the best restart from it") {
    const SidelobeObjective obj;
    SearchOptions o = options();
    o.threads = 3;
    IslandOptions isl;
    isl.migrate_every = 300;  // boundaries after each restart (600 moves): chains still differ
    isl.checkpoint_every = 300;
    int checked = 0, adopted = 0;
    // The checkpoint sees the states right after the migration of the same boundary.
    isl.checkpoint = [&](std::int64_t, std::int64_t every, const std::vector<ChainState>& states) {
        CHECK(every == 300);
        const TopCandidates::Item* best = nullptr;
        for (const ChainState& s : states) {
            const auto& top = s.top.items();
            if (!top.empty() && (!best || TopCandidates::less(top.front(), *best)))
                best = &top.front();
        }
        REQUIRE(best != nullptr);
        for (const ChainState& s : states) {
            const bool worse = s.top.items().front().objective > best->objective;
            CHECK(s.start.has_value() == worse);
            if (s.start) {
                CHECK(s.start->pinholes == best->pattern.pinholes);
                ++adopted;
            }
            ++checked;
        }
        CHECK(migration_message(states).size() ==
              8 + 8 + 8 * 5 + 16 * best->pattern.pinholes.size());
    };
    LocalComm comm;
    const SearchSummary a = run_island_search(comm, obj, o, sample, isl);
    const SearchSummary b = run_island_search(comm, obj, o, sample, isl);
    CHECK(checked >= 2 * 3 * 3);
    CHECK(adopted > 0);
    check_same(a, b);  // deterministic
    IslandOptions none;
    const SearchSummary c = run_island_search(comm, obj, o, sample, none);
    check_same(c, run_search(obj, o, sample));  // no migration: the plain search
}
