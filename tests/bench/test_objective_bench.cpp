// bench_objective (the search-objective figure of `pinmask bench search`): the records are
// complete and consistent. Speed itself is never asserted (no wall-clock limits in tests); the
// figure is in docs/benchmarks.md.
#include <doctest/doctest.h>

#include "bench/search_bench.hpp"

TEST_CASE("bench_objective: one record per geometry, per-cell rate = moves/s x n^2") {
    const auto rec = pinmask::bench_objective({{8, 4}, {12, 3}}, 0.01, 1);
    REQUIRE(rec.size() == 2);
    CHECK(rec[0].n == 8);
    CHECK(rec[0].pixels_per_cell == 4);
    CHECK(rec[1].n == 12);
    for (const auto& r : rec) {
        CHECK(r.holes >= 1);
        CHECK(r.moves_per_second > 0.0);
        CHECK(r.full_evals_per_second > 0.0);
        CHECK(r.per_cell_rate == doctest::Approx(r.moves_per_second * r.n * r.n));
    }
}
