#include "bench/search_bench.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <random>

#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/search/mask_objective.hpp"
#include "optimize/search/pattern_state.hpp"

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

std::vector<ObjectiveBenchRecord> bench_objective(const std::vector<std::pair<int, int>>& configs,
                                                  double seconds, std::uint64_t seed) {
    std::vector<ObjectiveBenchRecord> out;
    for (const auto& config : configs) {
        const int n = config.first, ppc = config.second;  // named: lambdas capture them
        Mask mask;
        mask.camera = paper_camera();
        mask.psf.pixels_per_cell = ppc;
        mask.pattern = start_pattern(n);
        const int m = n * ppc;
        check_psf_memory(n, ppc, 4, 2);
        const Kernel kernel = mask_kernel(mask);
        PriorSpec prior;
        prior.count = 2;
        auto model = std::make_shared<AnalyticWienerModel>(
            expand_half_spectrum(kernel_spectrum(kernel, n, ppc), m), make_scene_prior(prior, m),
            NoiseModel{});
        const MaskObjective objective(ObjectiveWeights{}, model, {WienerFilterKind::kOptimal, 0.0});
        PatternState state(mask.pattern);
        std::mt19937_64 rng(seed);
        std::uniform_int_distribution<int> hole(0, state.holes() - 1), cell(0, n - 1);
        double sink = 0.0;
        ObjectiveBenchRecord r;
        r.n = n;
        r.pixels_per_cell = ppc;
        r.holes = state.holes();
        sink += objective.evaluate(state);  // builds the alias tables outside the timing
        r.moves_per_second = rate(seconds, [&] {
            const int j = hole(rng);
            const Cell to{cell(rng), cell(rng)};
            if (state.is_legal_move(j, to)) state.move(j, to);
            sink += objective.evaluate(state);
        });
        const Fft2 fft(m, m);
        ComplexPlane half;
        r.full_evals_per_second = rate(seconds / 4.0, [&] {
            fft.forward(synthesize_psf(state.pattern(), kernel, ppc), half);
            sink += half(0, 0).real();
        });
        r.per_cell_rate = r.moves_per_second * n * n;
        if (!std::isfinite(sink)) r.moves_per_second = 0.0;  // keeps the work observable
        out.push_back(r);
    }
    return out;
}

}  // namespace pinmask
