// bench/depth_bench: the NIR camera's depth run beside an FFT pair. The timings are not held to
// anything here (docs/benchmarks.md records them); the run itself is: its period, its figures
// against depth_analysis on the same mask settings, and its refusals.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>

#include "bench/depth_bench.hpp"
#include "core/errors/error.hpp"

using namespace pinmask;

TEST_CASE("bench depth: the NIR camera's 544 px period, 2 distances, Wiener only") {
    DepthBenchOptions o;
    o.distances = 2;  // 0.9 m and 2 m: both far from the 1.2 m the pitch is whole at
    o.with_tv = false;
    o.rows = o.cols = 64;
    o.repeat = 1;
    const DepthBenchResult r = bench_depth(o);
    CHECK(r.period_px == 544);
    CHECK(r.distances == 2);
    // 0.9 m is 15.5 px of mismatch across the period: a clear loss (4 dB in docs/benchmarks.md).
    CHECK(r.worst_wiener_loss_db > 1.0);
    CHECK(r.depth_seconds > 0.0);
    CHECK(r.fft_pair_seconds > 0.0);
}

TEST_CASE("bench depth: options out of range are refused, naming the field") {
    DepthBenchOptions o;
    o.distances = 1;
    CHECK_THROWS_WITH_AS(bench_depth(o), doctest::Contains("distances"), InvalidInput);
    o = {};
    o.rows = 10;
    CHECK_THROWS_WITH_AS(bench_depth(o), doctest::Contains("rows"), InvalidInput);
    o = {};
    o.repeat = 0;
    CHECK_THROWS_WITH_AS(bench_depth(o), doctest::Contains("repeat"), InvalidInput);
}
