// The upper bound on the analytic Wiener PSNR of any K-pinhole pattern
// (optimize/search/objective_bound): above every pattern tried (random, MURA, hill-climbed,
// searched) under Gaussian and photon noise; equal to it where only one spectrum exists (K = 1, K =
// n^2); above the best of an exhaustive enumeration of 4 x 4 patterns and close to it; the relaxed
// optimum agrees with an independent Frank-Wolfe solver on the dense per-pixel formula; the
// water-filling satisfies KKT.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/search/objective_bound.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "tests/optimize/search/bound_setup.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// K = 1 and K = n^2 have one pattern spectrum each; bound and evaluation are the same sums in
// another order: round-off only.
constexpr double kExactTolRel = 1e-11;
// Exhaustive 4 x 4, K = 3..5: the relaxation (no binary, no symmetry constraint) is at most this
// far above the best pattern. Photon noise (the variance is exact): measured 0.05-0.18 dB
// (printed), 0.3 dB with margin. Gaussian SNR (the variance taken at the smallest mean(c^2) of
// the relaxed set, below every binary pattern's): measured 0.74-1.17 dB, 1.5 dB with margin.
constexpr double kExhaustiveGapPhotonDb = 0.3;
constexpr double kExhaustiveGapGaussianDb = 1.5;
// Duality gap of the water-filling (primal at x(mu) against the dual value): bisection on mu to
// 1e-13 of n^2 in the sum, Newton roots to 1e-15: measured <= 1e-12 relative; 1e-9 with margin.
constexpr double kDualityGapRel = 1e-9;
// KKT: interior x_a must have -g_a'(x_a) = mu. The roots are solved to 1e-15 in x, the slope
// recomputed here by a different summation: 1e-8 relative with margin.
constexpr double kKktTolRel = 1e-8;
// The water-filling's sum of x: bisection stops within 1e-13 n^2 = 6.4e-12 of it; 1e-10 margin.
constexpr double kSumTol = 1e-10;
// Frank-Wolfe with exact line search, 3000 iterations on 15 variables: its value approaches the
// relaxed optimum from above and its linearisation bound from below; measured within 1e-7
// relative; 1e-5 with margin.
constexpr double kFrankWolfeTolRel = 1e-5;
// Central differences of the relaxed objective (x in [0, 1], smooth): truncation ~1e-12 of the
// gradient, well inside what the line search and kFrankWolfeTolRel need.
constexpr double kFiniteDifferenceStep = 1e-6;

double optimal_psnr(const AnalyticWienerModel& model, const Pattern& p) {
    return model.evaluate(pattern_spectrum(p), {WienerFilterKind::kOptimal, 0.0}).psnr_db;
}

double bound_psnr(const std::shared_ptr<const AnalyticWienerModel>& model, int n, int k) {
    ObjectiveBoundOptions o;
    o.holes = k;
    return ObjectiveBoundModel(model, n).bound(o).psnr_db;
}

// Hill climbing by single-pinhole moves on the optimal-filter PSNR (a second "searched" route).
Pattern hill_climb(const AnalyticWienerModel& model, int n, int k, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Pattern best = random_pattern(n, k, rng);
    double best_psnr = optimal_psnr(model, best);
    std::uniform_int_distribution<int> cell(0, n * n - 1), hole(0, k - 1);
    for (int it = 0; it < 1500; ++it) {
        Pattern t = best;
        const int c = cell(rng);
        const Cell to{c / n, c % n};
        if (std::any_of(t.pinholes.begin(), t.pinholes.end(),
                        [&](const Cell& h) { return h.row == to.row && h.col == to.col; }))
            continue;
        t.pinholes[static_cast<std::size_t>(hole(rng))] = to;
        const double psnr = optimal_psnr(model, t);
        if (psnr > best_psnr) best = t, best_psnr = psnr;
    }
    return best;
}

}  // namespace

TEST_CASE("objective bound: above every random and hill-climbed pattern, every filter and noise") {
    const int n = 8, m = 40;
    for (const NoiseModel& noise : noise_models()) {
        const auto model = make_model(m, 3, noise);
        for (int k : {2, 5, 10, 16, 24, 40, 63}) {
            const double bound = bound_psnr(model, n, k);
            CAPTURE(k);
            CAPTURE(bound);
            std::mt19937_64 rng(static_cast<std::uint64_t>(k));
            double best = -INFINITY;
            for (int d = 0; d < 12; ++d) {
                const Pattern p = random_pattern(n, k, rng);
                const ComplexPlane spec = pattern_spectrum(p);
                const double opt = optimal_psnr(*model, p);
                best = std::max(best, opt);
                CHECK(opt <= bound + kBoundTolDb);
                CHECK(model->evaluate_tuned_nsr(spec).psnr_db <= bound + kBoundTolDb);
                CHECK(model->evaluate(spec, {WienerFilterKind::kFixedNsr, 1e-3}).psnr_db <=
                      bound + kBoundTolDb);
            }
            if (k == 10 || k == 24) {
                const double climbed = optimal_psnr(*model, hill_climb(*model, n, k, 7));
                CHECK(climbed >= best);                 // the climb did its job...
                CHECK(climbed <= bound + kBoundTolDb);  // ...and stays below the bound
                MESSAGE("noise " << static_cast<int>(noise.kind) << " K " << k << ": random best "
                                 << best << ", climbed " << climbed << ", bound " << bound);
            }
        }
    }
}

TEST_CASE("objective bound: above the MURA of order 13 under every noise model") {
    const int n = 13, m = 39;
    const Pattern mura = mura_pattern(13);
    const int k = static_cast<int>(mura.pinholes.size());
    for (const NoiseModel& noise : noise_models()) {
        const auto model = make_model(m, 2, noise);
        const double bound = bound_psnr(model, n, k), psnr = optimal_psnr(*model, mura);
        CAPTURE(bound);
        CAPTURE(psnr);
        CHECK(psnr <= bound + kBoundTolDb);
    }
}

TEST_CASE("objective bound: exact where only one spectrum exists (K = 1 and K = n^2)") {
    const int n = 8, m = 40;
    for (const NoiseModel& noise : noise_models()) {
        const auto model = make_model(m, 3, noise);
        ObjectiveBoundModel bm(model, n);
        Pattern one, full;
        one.n = full.n = n;
        one.pinholes = {{3, 5}};
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) full.pinholes.push_back({r, c});
        ObjectiveBoundOptions o;
        o.holes = 1;
        const double mse_one =
            model->evaluate(pattern_spectrum(one), {WienerFilterKind::kOptimal, 0.0}).mse;
        CHECK_CLOSE(bm.bound(o).mse, mse_one, kExactTolRel);
        o.holes = n * n;
        const double mse_full =
            model->evaluate(pattern_spectrum(full), {WienerFilterKind::kOptimal, 0.0}).mse;
        CHECK_CLOSE(bm.bound(o).mse, mse_full, kExactTolRel);
    }
}

TEST_CASE("objective bound: above the best of every 4 x 4 pattern with K = 3..5, and close") {
    const int n = 4, m = 8;
    for (const NoiseModel& noise : {photons(3.0, 3.0), gaussian(20.0)}) {
        const auto model = make_model(m, 1, noise);
        for (int k = 3; k <= 5; ++k) {
            double best = -INFINITY;
            std::vector<int> pick(16, 0);
            std::fill(pick.end() - k, pick.end(), 1);
            int count = 0;
            do {
                Pattern p;
                p.n = n;
                for (int i = 0; i < 16; ++i)
                    if (pick[i]) p.pinholes.push_back({i / n, i % n});
                best = std::max(best, optimal_psnr(*model, p));
                ++count;
            } while (std::next_permutation(pick.begin(), pick.end()));
            const double bound = bound_psnr(model, n, k);
            MESSAGE("K " << k << ": " << count << " patterns, best " << best << " dB, bound "
                         << bound << " dB, gap " << bound - best << " dB");
            CHECK(best <= bound + kBoundTolDb);
            CHECK(bound - best <= (noise.kind == NoiseKind::kPhoton ? kExhaustiveGapPhotonDb
                                                                    : kExhaustiveGapGaussianDb));
        }
    }
}

TEST_CASE("objective bound: the relaxed optimum agrees with Frank-Wolfe on the dense formula") {
    // Independent path: the relaxed objective evaluated by wiener_mse on the full m x m plane
    // h(k) = x(k mod n) kp(k), gradient by central differences, the linear minimisation over
    // {0 <= x <= 1, sum x = X} by filling the most negative gradients, exact line search by
    // golden section.
    const int n = 4, m = 8, k = 3;
    const auto model = make_model(m, 1, photons(3.0, 3.0));
    ObjectiveBoundOptions o;
    o.holes = k;
    const ObjectiveBound b = ObjectiveBoundModel(model, n).bound(o);
    const double sigma2 = b.noise_variance, target = 16.0 / k - 1.0;
    const auto f = [&](const std::vector<double>& x) {
        Plane h(m, m);
        for (int r = 0; r < m; ++r)
            for (int c = 0; c < m; ++c)
                h(r, c) =
                    x[static_cast<std::size_t>((r % n) * n + c % n)] * model->kernel_power()(r, c);
        return wiener_mse(h, model->prior().power, sigma2, {WienerFilterKind::kOptimal, 0.0});
    };
    std::vector<double> x(16, target / 15.0);
    x[0] = 1.0;
    double lower = -INFINITY;
    for (int it = 0; it < 3000; ++it) {
        std::vector<double> g(16, 0.0);
        for (int a = 1; a < 16; ++a) {
            const double step = kFiniteDifferenceStep;
            auto up = x, down = x;
            up[a] += step, down[a] -= step;
            g[a] = (f(up) - f(down)) / (2.0 * step);
        }
        std::vector<int> order(15);
        std::iota(order.begin(), order.end(), 1);
        std::sort(order.begin(), order.end(), [&](int i, int j) { return g[i] < g[j]; });
        std::vector<double> s(16, 0.0);
        s[0] = 1.0;
        double left = target;
        for (int a : order) s[a] = std::min(1.0, std::max(0.0, left)), left -= s[a];
        double gap = 0.0;
        for (int a = 1; a < 16; ++a) gap += g[a] * (s[a] - x[a]);
        lower = std::max(lower, f(x) + gap);  // convexity: f(y) >= f(x) + g.(y - x)
        double lo = 0.0, hi = 1.0;            // golden section on the segment x -> s
        const auto at = [&](double t) {
            auto y = x;
            for (int a = 1; a < 16; ++a) y[a] += t * (s[a] - x[a]);
            return f(y);
        };
        for (int i = 0; i < 60; ++i) {
            const double t1 = hi - 0.618033988749895 * (hi - lo),
                         t2 = lo + 0.618033988749895 * (hi - lo);
            if (at(t1) < at(t2))
                hi = t2;
            else
                lo = t1;
        }
        const double t = 0.5 * (lo + hi);
        for (int a = 1; a < 16; ++a) x[a] += t * (s[a] - x[a]);
    }
    const double upper = f(x);
    MESSAGE("Frank-Wolfe " << lower << " <= opt <= " << upper << "; water-filling dual " << b.mse
                           << ", primal " << b.relaxed_mse);
    CHECK(b.mse <= upper * (1.0 + kFrankWolfeTolRel));          // bound below FW's feasible value
    CHECK(b.mse >= lower * (1.0 - kFrankWolfeTolRel));          // and not below FW's lower bound
    CHECK(b.relaxed_mse <= upper * (1.0 + kFrankWolfeTolRel));  // the water-filling is optimal
}

TEST_CASE("objective bound: the water-filling satisfies the KKT conditions") {
    const int n = 8, m = 40;
    for (const NoiseModel& noise : noise_models()) {
        const auto model = make_model(m, 3, noise);
        const ObjectiveBoundModel bm(model, n);
        for (int k : {3, 10, 30}) {
            ObjectiveBoundOptions o;
            o.holes = k;
            const ObjectiveBound b = bm.bound(o);
            const double nu = b.noise_variance * m * m, mu = b.multiplier;
            CAPTURE(k);
            CAPTURE(mu);
            REQUIRE(b.x.size() == 64u);
            CHECK(b.x[0] == 1.0);
            double sum = 0.0;
            for (double v : b.x) {
                CHECK(v >= 0.0);
                CHECK(v <= 1.0);
                sum += v;
            }
            CHECK(std::fabs(sum - 64.0 / k) <= kSumTol);  // Parseval's sum, active here
            CHECK(mu > 0.0);
            CHECK(b.relaxed_mse >= b.mse);
            CHECK_CLOSE(b.relaxed_mse, b.mse, kDualityGapRel);
            // -g_a'(x) recomputed from the model's planes directly (not the grouped terms).
            const Plane& kp = model->kernel_power();
            const Plane& s = model->prior().power;
            for (int a = 1; a < 64; ++a) {
                double phi = 0.0;
                for (int r = a / n; r < m; r += n)
                    for (int c = a % n; c < m; c += n) {
                        const double cc = kp(r, c) * s(r, c), d = b.x[a] * cc + nu;
                        phi += s(r, c) * cc * nu / (d * d);
                    }
                CAPTURE(a);
                CAPTURE(b.x[a]);
                if (b.x[a] > 0.0 && b.x[a] < 1.0) CHECK_CLOSE(phi, mu, kKktTolRel);
                if (b.x[a] == 0.0) CHECK(phi <= mu * (1.0 + kKktTolRel));
                if (b.x[a] == 1.0) CHECK(phi >= mu * (1.0 - kKktTolRel));
            }
        }
    }
}

TEST_CASE("objective bound: options are validated, naming the field") {
    const auto model = make_model(40, 3, photons(3.0, 3.0));
    const ObjectiveBoundModel bm(model, 8);
    ObjectiveBoundOptions o;
    for (int bad : {0, -1, 65}) {
        o.holes = bad;
        CHECK_THROWS_WITH_AS(bm.bound(o), doctest::Contains("holes"), InvalidInput);
    }
    o.holes = 5;
    o.sum_tolerance = NAN;
    CHECK_THROWS_WITH_AS(bm.bound(o), doctest::Contains("sum_tolerance"), InvalidInput);
    o.sum_tolerance = 1e-13;
    o.max_iterations = 0;
    CHECK_THROWS_WITH_AS(bm.bound(o), doctest::Contains("max_iterations"), InvalidInput);
    CHECK_THROWS_AS(ObjectiveBoundModel(model, 7), InvalidInput);  // 7 does not divide 40
    CHECK_THROWS_AS(ObjectiveBoundModel(nullptr, 8), InvalidInput);
}

TEST_CASE("search reports the bound per K, above every best mask") {
    SearchPipelineOptions o;
    o.tmpl.camera = paper_camera();
    o.tmpl.pattern.n = 16;
    o.tmpl.pattern.min_spacing_cells = 2.0;
    o.tmpl.psf.pixels_per_cell = 8;
    o.holes = 8;
    o.max_holes = 14;
    o.noise = photons(3.0, 3.0);
    o.filter = {WienerFilterKind::kTunedNsr, 0.0};
    o.search.threads = 1;
    o.search.time_budget_s = 0.0;
    o.search.max_evaluations = 600;
    o.search.top = 2;
    o.rerank_scenes.clear();
    const SearchPipelineSummary s = run_search_pipeline(o);
    REQUIRE(!s.best_per_holes.empty());
    for (const RankedMask& r : s.best_per_holes) {
        const int k = static_cast<int>(r.mask.pattern.pinholes.size());
        CAPTURE(k);
        REQUIRE(std::isfinite(r.upper_bound_psnr_db));
        CHECK(r.mask.provenance.scores.at("analytic_mmse_psnr_db") <=
              r.upper_bound_psnr_db + kBoundTolDb);
    }
    for (const RankedMask& r : s.ranked) CHECK(std::isfinite(r.upper_bound_psnr_db));
}

TEST_CASE(
    "dim light: the bound is above every random and searched mask; its gap to the best per-K "
    "random median (printed)") {
    // The setup of "search --holes 5..40 beats the best median random mask of any single K (dim
    // light)" (tests/optimize/search/test_search_holes.cpp): paper camera, 16 x 16, 8 px per cell,
    // photon model 3 e- per pinhole per pixel, read noise 3 e-, the expected PSNR over the
    // natural-scene family (1024 scenes of seeds 20000..), the same random masks (7 per K, seeds
    // 1000 K + d).
    const int n = kDimLightN, draws = 7;
    const Mask tmpl = dim_light_template();
    const auto model = dim_light_model();
    const ObjectiveBoundModel bounds(model, n);
    double best_bound = -INFINITY, best_tuned = -INFINITY, best_optimal = -INFINITY;
    int bound_k = 0, tuned_k = 0, optimal_k = 0;
    for (int k = 5; k <= 40; ++k) {
        ObjectiveBoundOptions o;
        o.holes = k;
        const double bound = bounds.bound(o).psnr_db;
        RandomSparseOptions ro;
        ro.n = n;
        ro.holes = k;
        std::vector<double> tuned, optimal;
        for (int d = 0; d < draws; ++d) {
            std::mt19937_64 rng(static_cast<std::uint64_t>(1000 * k + d));
            const ComplexPlane spec = pattern_spectrum(random_sparse_pattern(ro, rng));
            tuned.push_back(model->evaluate_tuned_nsr(spec).psnr_db);
            optimal.push_back(model->evaluate(spec, {WienerFilterKind::kOptimal, 0.0}).psnr_db);
            CHECK(tuned.back() <= bound + kBoundTolDb);
            CHECK(optimal.back() <= bound + kBoundTolDb);
        }
        std::sort(tuned.begin(), tuned.end());
        std::sort(optimal.begin(), optimal.end());
        const double tuned_median = tuned[draws / 2], optimal_median = optimal[draws / 2];
        MESSAGE("K " << k << ": bound " << bound << " dB, random median tuned-NSR " << tuned_median
                     << " dB, optimal filter " << optimal_median << " dB");
        if (bound > best_bound) best_bound = bound, bound_k = k;
        if (tuned_median > best_tuned) best_tuned = tuned_median, tuned_k = k;
        if (optimal_median > best_optimal) best_optimal = optimal_median, optimal_k = k;
    }
    // A mask searched on the optimal filter's PSNR (the bound's filter), its own 16-scene prior:
    // how close a search comes to the bound.
    SearchPipelineOptions so;
    so.tmpl = tmpl;
    so.holes = 5;
    so.max_holes = 40;
    so.noise = photons(3.0, 3.0);
    so.filter = {WienerFilterKind::kOptimal, 0.0};
    so.search.threads = 1;
    so.search.time_budget_s = 0.0;
    so.search.max_evaluations = 6000;
    so.search.anneal_restart_moves = 3000;
    so.search.top = 1;
    so.rerank_scenes.clear();
    const SearchPipelineSummary found = run_search_pipeline(so);
    REQUIRE(!found.ranked.empty());
    const Pattern& fp = found.ranked.front().mask.pattern;
    const int found_k = static_cast<int>(fp.pinholes.size());
    ObjectiveBoundOptions fo;
    fo.holes = found_k;
    const double found_bound = bounds.bound(fo).psnr_db;
    const ComplexPlane fs = pattern_spectrum(fp);
    const double found_optimal = model->evaluate(fs, {WienerFilterKind::kOptimal, 0.0}).psnr_db;
    CHECK(found_optimal <= found_bound + kBoundTolDb);
    MESSAGE("searched (optimal filter objective): K "
            << found_k << ", expected " << found_optimal << " dB optimal filter, "
            << model->evaluate_tuned_nsr(fs).psnr_db << " dB tuned NSR; bound at its K "
            << found_bound << " dB");
    MESSAGE("max over K of the bound: "
            << best_bound << " dB (K = " << bound_k
            << "); best random median, tuned NSR: " << best_tuned << " dB (K = " << tuned_k
            << "), gap " << best_bound - best_tuned << " dB; optimal filter: " << best_optimal
            << " dB (K = " << optimal_k << "), gap " << best_bound - best_optimal << " dB");
}
