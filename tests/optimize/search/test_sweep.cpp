// optimize/search/sweep and optimize/search/work_queue without MPI ranks: the result codec
// round-trips and refuses damaged bytes, a sweep equals one search per point run directly (a second
// code path: run_search_pipeline itself), and the work queue returns results by index and reports
// the lowest failed item.
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/search/sweep.hpp"
#include "optimize/search/work_queue.hpp"

using namespace pinmask;

namespace {

SearchPipelineOptions small_point(int holes, std::uint64_t seed) {
    SearchPipelineOptions o;
    o.tmpl.pattern.n = 8;
    o.tmpl.pattern.tiles_rows = o.tmpl.pattern.tiles_cols = 1;
    o.tmpl.psf.pixels_per_cell = 4;
    o.holes = holes;
    o.search.threads = 1;
    o.search.time_budget_s = 0.0;
    o.search.max_evaluations = 60;
    o.search.seed = seed;
    o.search.top = 2;
    o.prior.count = 2;
    return o;
}

}  // namespace

TEST_CASE("sweep result bytes round-trip and damaged bytes are refused") {
    SweepPointResult r;
    r.pattern.n = 9;
    r.pattern.tiles_rows = 2;
    r.pattern.tiles_cols = 3;
    r.pattern.min_spacing_cells = 2.5;
    r.pattern.pinholes = {{0, 1}, {4, 7}, {8, 8}};
    r.scores = {{"analytic_wiener_psnr_db", 21.25}, {"max_sidelobe", 2.0}};
    r.objective = -21.25;
    r.reranked = true;
    r.evaluations = 123456789012LL;
    r.kernel_resolved = "fresnel";
    const std::string bytes = encode_sweep_result(r);
    const SweepPointResult back = decode_sweep_result(bytes);
    CHECK(back.pattern.n == 9);
    CHECK(back.pattern.tiles_rows == 2);
    CHECK(back.pattern.tiles_cols == 3);
    CHECK(back.pattern.min_spacing_cells == 2.5);
    CHECK(back.pattern.pinholes == r.pattern.pinholes);
    CHECK(back.scores == r.scores);
    CHECK(back.objective == r.objective);
    CHECK(back.reranked);
    CHECK(back.evaluations == r.evaluations);
    CHECK(back.kernel_resolved == "fresnel");
    CHECK(encode_sweep_result(back) == bytes);
    for (std::size_t cut : {std::size_t(0), std::size_t(3), bytes.size() / 2, bytes.size() - 1})
        CHECK_THROWS_AS(decode_sweep_result(bytes.substr(0, cut)), RuntimeFailure);
    CHECK_THROWS_AS(decode_sweep_result(bytes + "x"), RuntimeFailure);
    std::string wrong = bytes;
    wrong[0] ^= 1;
    CHECK_THROWS_AS(decode_sweep_result(wrong), RuntimeFailure);
}

TEST_CASE("a sweep is one search per point: same best masks as running each search directly") {
    const std::vector<SearchPipelineOptions> points{small_point(3, 1), small_point(4, 1),
                                                    small_point(4, 2)};
    std::vector<int> done_order;
    LocalComm comm;
    const std::vector<SweepPointResult> results =
        run_sweep(comm, points, [&](int done, int count, int index) {
            CHECK(count == 3);
            CHECK(done == static_cast<int>(done_order.size()) + 1);
            done_order.push_back(index);
        });
    REQUIRE(results.size() == 3);
    CHECK(done_order == std::vector<int>{0, 1, 2});
    for (std::size_t i = 0; i < points.size(); ++i) {
        CAPTURE(i);
        const SearchPipelineSummary direct = run_search_pipeline(points[i]);
        REQUIRE(!direct.ranked.empty());
        const Mask& expected = direct.ranked.front().mask;
        const Mask got = sweep_best_mask(points[i], results[i]);
        CHECK(got.pattern.pinholes == expected.pattern.pinholes);
        CHECK(got.pattern.n == expected.pattern.n);
        CHECK(got.provenance.scores == expected.provenance.scores);
        CHECK(got.provenance.seed == expected.provenance.seed);
        CHECK(got.provenance.family == expected.provenance.family);
        CHECK(geometry_hash(got) == geometry_hash(expected));
        CHECK(results[i].objective == direct.ranked.front().objective);
        CHECK(results[i].evaluations == direct.search.evaluations);
        CHECK(static_cast<int>(got.pattern.pinholes.size()) == points[i].holes);
    }
}

TEST_CASE("work queue (one process): results by index, the lowest failure reported") {
    LocalComm comm;
    const WorkQueueResult ok = run_work_queue(
        comm, 4, [](int i) { return std::string(static_cast<std::size_t>(i), 'a'); });
    CHECK(ok.failed_index == -1);
    REQUIRE(ok.results.size() == 4);
    for (int i = 0; i < 4; ++i)
        CHECK(ok.results[i] == std::string(static_cast<std::size_t>(i), 'a'));
    int ran = 0;
    const WorkQueueResult bad = run_work_queue(comm, 5, [&](int i) -> std::string {
        ++ran;
        if (i == 1) throw InvalidInput("holes: bad");
        if (i == 3) throw std::runtime_error("later");
        return "x";
    });
    CHECK(bad.failed_index == 1);
    CHECK(bad.failure == "holes: bad");
    CHECK(bad.failure_invalid_input);
    CHECK(bad.results.empty());
    CHECK(ran == 2);  // one process stops at the first failure
}
