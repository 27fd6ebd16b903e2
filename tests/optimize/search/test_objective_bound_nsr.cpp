// The scalar-NSR bound (tests/research/objective_bound_nsr): above every pattern's tuned-NSR
// PSNR (random 8 x 8, every 4 x 4 pattern with K = 3..5), never above the optimal filter's bound,
// equal to it when the NSR axis is one interval; options validated; and the dim-light
// measurement (slow: CTest label slow, skipped by the default run).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/search/objective_bound.hpp"
#include "tests/optimize/search/bound_setup.hpp"
#include "tests/research/objective_bound_nsr.hpp"

using namespace pinmask;
using namespace pinmask::test;

namespace {

// Exhaustive 4 x 4, K = 3..5, tuned NSR: the scalar-NSR bound is at most this far above the
// best pattern. Measured 0.27-2.02 dB (printed; 16 cells leave binary patterns far from the
// relaxed spectra); 3 dB with margin.
constexpr double kExhaustiveScalarGapDb = 3.0;
// Scalar-NSR bound, whole NSR axis as one interval against the optimal filter's relaxed
// minimum: below it up to round-off (kBoundTolRel), above it by at most the inner branch and
// bound's tolerance (1e-3 of each group's prior power: measured within 1e-3; 1e-2 with margin).
constexpr double kBoundTolRel = 1e-12;
constexpr double kWholeAxisTolRel = 1e-2;

double bound_psnr(const std::shared_ptr<const AnalyticWienerModel>& model, int n, int k) {
    ObjectiveBoundOptions o;
    o.holes = k;
    return ObjectiveBoundModel(model, n).bound(o).psnr_db;
}

}  // namespace

TEST_CASE("scalar-NSR bound: above every pattern's tuned-NSR PSNR, below the optimal bound") {
    const int n = 8, m = 40;
    for (const NoiseModel& noise : {photons(3.0, 3.0), gaussian(30.0)}) {
        const auto model = make_model(m, 3, noise);
        const NsrBoundModel nb(model, n);
        for (int k : {3, 10, 24}) {
            NsrBoundOptions o;
            o.holes = k;
            const NsrBound b = nb.bound(o);
            const double optimal = bound_psnr(model, n, k);
            CAPTURE(k);
            CAPTURE(b.psnr_db);
            CHECK(b.psnr_db <= optimal + kBoundTolDb);
            std::mt19937_64 rng(static_cast<std::uint64_t>(k));
            double best = -INFINITY;
            for (int d = 0; d < 12; ++d) {
                const ComplexPlane spec = pattern_spectrum(random_pattern(n, k, rng));
                const double tuned = model->evaluate_tuned_nsr(spec).psnr_db;
                best = std::max(best, tuned);
                CHECK(tuned <= b.psnr_db + kBoundTolDb);
            }
            MESSAGE("noise " << static_cast<int>(noise.kind) << " K " << k << ": optimal bound "
                             << optimal << ", scalar-NSR bound " << b.psnr_db << " (NSR "
                             << b.nsr_lo << ".." << b.nsr_hi << ", " << b.intervals
                             << " intervals), best random tuned " << best);
        }
    }
}

TEST_CASE(
    "scalar-NSR bound: above every 4 x 4 pattern's tuned-NSR PSNR (K = 3..5); the whole "
    "NSR axis as one interval is the optimal filter's bound") {
    const int n = 4, m = 8;
    for (const NoiseModel& noise : {photons(3.0, 3.0), gaussian(20.0)}) {
        const auto model = make_model(m, 1, noise);
        const NsrBoundModel nb(model, n);
        const ObjectiveBoundModel ob(model, n);
        for (int k = 3; k <= 5; ++k) {
            double best = -INFINITY;
            std::vector<int> pick(16, 0);
            std::fill(pick.end() - k, pick.end(), 1);
            do {
                Pattern p;
                p.n = n;
                for (int i = 0; i < 16; ++i)
                    if (pick[i]) p.pinholes.push_back({i / n, i % n});
                best = std::max(best, model->evaluate_tuned_nsr(pattern_spectrum(p)).psnr_db);
            } while (std::next_permutation(pick.begin(), pick.end()));
            NsrBoundOptions o;
            o.holes = k;
            const NsrBound b = nb.bound(o);
            MESSAGE("K " << k << ": best tuned-NSR " << best << " dB, scalar-NSR bound "
                         << b.psnr_db << " dB, gap " << b.psnr_db - best << " dB");
            CHECK(best <= b.psnr_db + kBoundTolDb);
            CHECK(b.psnr_db - best <= kExhaustiveScalarGapDb);
            // rho = clamp(B / S, 0, inf) = B / S is the optimal filter's term: the one-interval
            // bound is the optimal filter's relaxed minimum, up to the inner tolerance.
            ObjectiveBoundOptions oo;
            oo.holes = k;
            const ObjectiveBound opt = ob.bound(oo);
            const double nu = opt.noise_variance * m * m, big_n2 = std::pow(m * m, 2.0);
            const double whole = nb.interval_bound(0.0, INFINITY, nu, 16.0 / k - 1.0) / big_n2;
            CHECK(whole <= opt.relaxed_mse * (1.0 + kBoundTolRel));
            CHECK(whole >= opt.mse * (1.0 - kWholeAxisTolRel));
        }
    }
}

// Slow (CTest slow-nsr-bound-table, label slow; minutes in Release: one scalar-NSR bound per
// K = 5..40 at 16 x 16, 8 px per cell, 4 s each). Its CHECKs hold the bound above every random
// mask's tuned-NSR PSNR. Reproduces the Parseval-only scalar-NSR bound of docs/benchmarks.md
// "How far from the best possible": at most 19.58 dB over K = 5..40 (K = 40).
TEST_CASE("dim light: scalar-NSR bound over K = 5..40 against the best per-K random median" *
          doctest::skip()) {
    const int n = kDimLightN, draws = 7;
    const auto model = dim_light_model();
    const NsrBoundModel bounds(model, n);
    double best_bound = -INFINITY, best_tuned = -INFINITY;
    int bound_k = 0, tuned_k = 0;
    for (int k = 5; k <= 40; ++k) {
        NsrBoundOptions o;
        o.holes = k;
        const NsrBound b = bounds.bound(o);
        RandomSparseOptions ro;
        ro.n = n;
        ro.holes = k;
        std::vector<double> tuned;
        for (int d = 0; d < draws; ++d) {
            std::mt19937_64 rng(static_cast<std::uint64_t>(1000 * k + d));
            tuned.push_back(
                model->evaluate_tuned_nsr(pattern_spectrum(random_sparse_pattern(ro, rng)))
                    .psnr_db);
            CHECK(tuned.back() <= b.psnr_db + kBoundTolDb);
        }
        std::sort(tuned.begin(), tuned.end());
        MESSAGE("K " << k << ": scalar-NSR bound " << b.psnr_db << " dB (NSR " << b.nsr_lo << ".."
                     << b.nsr_hi << "), random median tuned-NSR " << tuned[draws / 2] << " dB");
        if (b.psnr_db > best_bound) best_bound = b.psnr_db, bound_k = k;
        if (tuned[draws / 2] > best_tuned) best_tuned = tuned[draws / 2], tuned_k = k;
    }
    MESSAGE("max over K of the scalar-NSR bound: "
            << best_bound << " dB (K = " << bound_k
            << "); best random median, tuned NSR: " << best_tuned << " dB (K = " << tuned_k
            << "), gap " << best_bound - best_tuned << " dB");
    MESSAGE("docs/benchmarks.md: the Parseval-only scalar-NSR bound is at most 19.58 dB (K = 40)");
}

TEST_CASE("scalar-NSR bound: options are validated, naming the field") {
    const auto model = make_model(40, 3, photons(3.0, 3.0));
    const NsrBoundModel nb(model, 8);
    NsrBoundOptions no;
    no.holes = 65;
    CHECK_THROWS_WITH_AS(nb.bound(no), doctest::Contains("holes"), InvalidInput);
    no.holes = 5;
    no.nsr_ratio = 1.0;
    CHECK_THROWS_WITH_AS(nb.bound(no), doctest::Contains("nsr_ratio"), InvalidInput);
    no.nsr_ratio = 1.05;
    no.max_intervals = 10;
    CHECK_THROWS_WITH_AS(nb.bound(no), doctest::Contains("max_intervals"), InvalidInput);
    no.max_intervals = 400;
    no.group_tolerance = NAN;
    CHECK_THROWS_WITH_AS(nb.bound(no), doctest::Contains("group_tolerance"), InvalidInput);
    CHECK_THROWS_AS(NsrBoundModel(model, 7), InvalidInput);
}
