// The decode benchmark's library part: one record per method and size, consistent ratios, and
// option validation. Timings themselves are never asserted.
#include <doctest/doctest.h>

#include <set>
#include <string>

#include "bench/decode_bench.hpp"
#include "core/errors/error.hpp"

using namespace pinmask;

TEST_CASE("bench_decode returns every method per size with ratio = seconds / fft pair") {
    DecodeBenchOptions o;
    o.sizes = {16, 24};
    o.repeat = 1;
    o.min_batch_seconds = 1e-4;
    o.tvqc_max_iterations = 20;
    const auto records = bench_decode(o);
    // 10 cyclic and 3 linear methods per size, plus tv_l2_to_0.2dB for the sizes 16 n_px (16
    // here, not 24).
    REQUIRE(records.size() == 27);
    std::set<std::string> methods;
    for (const auto& r : records) {
        methods.insert(r.method);
        CHECK((r.size == 16 || r.size == 24));
        CHECK(r.fft_pair_seconds > 0.0);
        CHECK(r.seconds_per_call >= 0.0);
        CHECK(r.ratio == doctest::Approx(r.seconds_per_call / r.fft_pair_seconds));
        CHECK(r.fft_pair_float_seconds > 0.0);
        CHECK(r.ratio_float == doctest::Approx(r.seconds_per_call / r.fft_pair_float_seconds));
        if (r.method == "tv_l2_to_0.2dB") CHECK(r.size == 16);
        // The floor in FFT pairs: one for the closed forms and a cyclic TV-L2 iteration, two for
        // the other iterations; none for the whole runs.
        const bool linear = r.method.find("_linear_") != std::string::npos;
        CHECK(r.model == (linear ? "linear" : "cyclic"));
        if (r.method.rfind("wiener", 0) == 0 || r.method == "tikhonov" ||
            r.method.rfind("tv_l2_iteration", 0) == 0) {
            CHECK(r.fft_pairs == 1);
        } else if (r.method.find("_to_") != std::string::npos) {
            CHECK(r.fft_pairs == 0);
        } else {
            CHECK(r.fft_pairs == 2);
        }
        if (r.method == "tvqc_to_tolerance") {
            CHECK(r.iterations >= 1);
            CHECK(r.iterations <= 20);
        }
    }
    CHECK(methods ==
          std::set<std::string>{"wiener", "wiener_single", "tikhonov", "tv_l2_iteration",
                                "tv_l2_iteration_single", "tv_l2_to_0.2dB", "tvqc_to_tolerance",
                                "tvqc_iteration", "tvqc_iteration_single", "rl_iteration",
                                "rl_iteration_single", "tv_l2_linear_iteration_single",
                                "tvqc_linear_iteration_single", "rl_linear_iteration_single"});
}

TEST_CASE("bench_decode validates its options, naming the field") {
    DecodeBenchOptions o;
    o.sizes = {8};
    CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("sizes"), InvalidInput);
    o.sizes = {};
    CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("sizes"), InvalidInput);
    o.sizes = {32};
    o.repeat = 0;
    CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("repeat"), InvalidInput);
    o.repeat = 1;
    o.tvqc_max_iterations = 0;
    CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("tvqc_max_iterations"), InvalidInput);
    o.tvqc_max_iterations = 1;
    for (int t : {0, -1, 1025}) {
        o.threads = t;
        CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("threads"), InvalidInput);
    }
    o.threads = 2;
    o.cpu_time = true;
    CHECK_THROWS_WITH_AS(bench_decode(o), doctest::Contains("cpu_time"), InvalidInput);
}
