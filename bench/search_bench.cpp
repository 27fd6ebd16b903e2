#include "bench/search_bench.hpp"

#include <chrono>
#include <random>

#include "optimize/pattern_state.hpp"

namespace pinmask {
namespace {

using Clock = std::chrono::steady_clock;

// Sparse legal start: pinholes on a lattice of step 4 (spacing 2), about n^2/64 of them capped
// at 4n so K grows like the paper's (K = 20 at n = 16).
Pattern start_pattern(int n) {
    Pattern p;
    p.n = n;
    const int want = std::max(1, std::min(n * n / 12, 4 * n));
    for (int r = 0; r + 3 < n && static_cast<int>(p.pinholes.size()) < want; r += 3)
        for (int c = 0; c + 3 < n && static_cast<int>(p.pinholes.size()) < want; c += 3)
            p.pinholes.push_back({r, c});
    return p;
}

template <class F>
double rate(double seconds, F&& step) {
    std::int64_t count = 0;
    const auto t0 = Clock::now();
    double elapsed = 0.0;
    do {
        for (int i = 0; i < 64; ++i) step();
        count += 64;
        elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    } while (elapsed < seconds);
    return static_cast<double>(count) / elapsed;
}

}  // namespace

std::vector<SearchBenchRecord> bench_search(const std::vector<int>& sizes, double seconds_per_size,
                                            std::uint64_t seed) {
    std::vector<SearchBenchRecord> out;
    for (int n : sizes) {
        const Pattern start = start_pattern(n);
        PatternState state(start);
        std::mt19937_64 rng(seed);
        std::uniform_int_distribution<int> cell(0, n - 1);
        std::uniform_int_distribution<int> hole(0, state.holes() - 1);
        SearchBenchRecord r;
        r.n = n;
        r.holes = state.holes();
        r.moves_per_second = rate(seconds_per_size, [&] {
            const int j = hole(rng);
            const Cell to{cell(rng), cell(rng)};
            if (state.is_legal_move(j, to)) state.move(j, to);
        });
        PatternState full(start);
        r.full_evals_per_second = rate(seconds_per_size, [&] { full.recompute(); });
        r.speedup = r.moves_per_second / r.full_evals_per_second;
        out.push_back(r);
    }
    return out;
}

}  // namespace pinmask
