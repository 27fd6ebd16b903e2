// decode/depthmap/smooth_labels against brute force: on a one-row volume the two row paths give the
// exact min-marginals of the chain energy (and so its exact minimiser), and on a small grid every
// path's message equals the minimum over all labellings of the chain that leads to the pixel,
// enumerated here label by label.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/errors/error.hpp"
#include "decode/depthmap/refine.hpp"
#include "decode/depthmap/smooth_labels.hpp"

using namespace pinmask;

namespace {

double pair_cost(int a, int b, double p1, double p2) {
    const int d = std::abs(a - b);
    return d == 0 ? 0.0 : d == 1 ? p1 : p2;
}

std::vector<Plane> random_volume(int rows, int cols, int k_count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Plane> v(k_count, Plane(rows, cols));
    for (auto& p : v)
        for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    return v;
}

// The minimum of sum C + sum V over the labellings of `chain` (pixel indices in order, the last
// one the pixel of interest) with the last pixel's label fixed to d, by enumeration.
double chain_minimum(const std::vector<Plane>& c, const std::vector<Eigen::Index>& chain, int d,
                     double p1, double p2) {
    const int k_count = static_cast<int>(c.size());
    const std::size_t free = chain.size() - 1;
    std::size_t configs = 1;
    for (std::size_t i = 0; i < free; ++i) configs *= std::size_t(k_count);
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> l(chain.size());
    for (std::size_t code = 0; code < configs; ++code) {
        std::size_t rest = code;
        for (std::size_t i = 0; i < free; ++i) {
            l[i] = int(rest % std::size_t(k_count));
            rest /= std::size_t(k_count);
        }
        l[free] = d;
        double e = 0.0;
        for (std::size_t i = 0; i < chain.size(); ++i) {
            e += c[std::size_t(l[i])].data()[chain[i]];
            if (i > 0) e += pair_cost(l[i - 1], l[i], p1, p2);
        }
        best = std::min(best, e);
    }
    return best;
}

}  // namespace

TEST_CASE("two row paths on one row give the exact minimiser of the chain energy") {
    const int cols = 7, k_count = 4;  // 4^7 = 16384 labellings
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const double p1 = 0.05 * seed, p2 = p1 * (seed % 2 ? 2.0 : 4.0);
        const std::vector<Plane> c = random_volume(1, cols, k_count, seed);
        // The brute-force minimum of E and its min-marginals.
        std::vector<double> marginal(std::size_t(cols * k_count),
                                     std::numeric_limits<double>::infinity());
        double e_min = std::numeric_limits<double>::infinity();
        std::vector<int> arg(cols), l(cols);
        for (int code = 0; code < 16384; ++code) {
            int rest = code;
            for (int j = 0; j < cols; ++j, rest /= k_count) l[j] = rest % k_count;
            double e = 0.0;
            for (int j = 0; j < cols; ++j) {
                e += c[std::size_t(l[j])](0, j);
                if (j > 0) e += pair_cost(l[j - 1], l[j], p1, p2);
            }
            if (e < e_min) {
                e_min = e;
                arg = l;
            }
            for (int j = 0; j < cols; ++j) {
                double& m = marginal[std::size_t(j * k_count + l[j])];
                m = std::min(m, e);
            }
        }
        const std::vector<Plane> s = aggregate_paths(c, p1, p2, 2);
        for (int j = 0; j < cols; ++j) {
            double s_min = s[0](0, j);
            int best = 0;
            for (int k = 1; k < k_count; ++k) {
                if (s[std::size_t(k)](0, j) < s_min) {
                    s_min = s[std::size_t(k)](0, j);
                    best = k;
                }
            }
            CHECK(best == arg[std::size_t(j)]);
            // S - min S is the min-marginal minus the minimum energy, label by label.
            for (int k = 0; k < k_count; ++k) {
                CHECK(
                    s[std::size_t(k)](0, j) - s_min ==
                    doctest::Approx(marginal[std::size_t(j * k_count + k)] - e_min).epsilon(1e-12));
            }
        }
    }
}

TEST_CASE("the column paths on one column are the same exact chain") {
    const std::vector<Plane> c = random_volume(6, 1, 3, 11);
    std::vector<Plane> t;
    for (const Plane& p : c) t.push_back(p.transpose());
    const std::vector<Plane> down = aggregate_paths(c, 0.1, 0.3, 4);
    const std::vector<Plane> along = aggregate_paths(t, 0.1, 0.3, 2);
    for (std::size_t k = 0; k < c.size(); ++k)
        for (int i = 0; i < 6; ++i) CHECK(down[k](i, 0) == doctest::Approx(along[k](0, i)));
}

TEST_CASE("every path's message on a grid is the chain minimum found by enumeration") {
    const int rows = 4, cols = 5, k_count = 3;
    const double p1 = 0.15, p2 = 0.4;
    const std::vector<Plane> c = random_volume(rows, cols, k_count, 5);
    const std::vector<Plane> s = aggregate_paths(c, p1, p2, 8);
    const int dirs[8][2] = {{0, 1}, {0, -1}, {1, 0}, {-1, 0}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            std::vector<double> ref(k_count), got(k_count);
            for (int d = 0; d < k_count; ++d) {
                const double cd = c[std::size_t(d)](i, j);
                ref[std::size_t(d)] = cd;
                for (const auto& r : dirs) {
                    // The chain that leads to (i, j) along r, from the frame's edge.
                    std::vector<Eigen::Index> chain;
                    int a = i, b = j;
                    while (a >= 0 && a < rows && b >= 0 && b < cols) {
                        chain.insert(chain.begin(), Eigen::Index(a) * cols + b);
                        a -= r[0];
                        b -= r[1];
                    }
                    ref[std::size_t(d)] += chain_minimum(c, chain, d, p1, p2) - cd;
                }
                got[std::size_t(d)] = s[std::size_t(d)](i, j);
            }
            // Each path's message is defined up to a constant per pixel.
            const double rmin = *std::min_element(ref.begin(), ref.end());
            const double gmin = *std::min_element(got.begin(), got.end());
            for (int d = 0; d < k_count; ++d)
                CHECK(got[std::size_t(d)] - gmin ==
                      doctest::Approx(ref[std::size_t(d)] - rmin).epsilon(1e-12));
        }
    }
}

TEST_CASE("zero penalties leave the costs, and the smoothing mends noisy labels") {
    const std::vector<Plane> c = random_volume(3, 4, 5, 2);
    const std::vector<Plane> s = aggregate_paths(c, 0.0, 0.0, 8);
    for (std::size_t k = 0; k < c.size(); ++k) CHECK((s[k] - c[k]).abs().maxCoeff() == 0.0);

    // Two regions (left plane 1, right plane 3) seen through noisy costs: the well at the true
    // plane is 0.3 deep, the noise uniform in [0, 1).
    const int rows = 24, cols = 24, k_count = 5;
    std::vector<Plane> v = random_volume(rows, cols, k_count, 9);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) v[j < cols / 2 ? 1 : 3](i, j) -= 0.3;
    auto wrong = [&](const std::vector<Plane>& vol) {
        const std::vector<double> inv{4, 3, 2, 1, 0.5};
        const RefinedDepth r = refine_depth(vol, inv);
        int n = 0;
        for (int i = 0; i < rows; ++i)
            for (int j = 0; j < cols; ++j) n += r.label(i, j) != (j < cols / 2 ? 1.0 : 3.0);
        return n;
    };
    const double scale = cost_well_depth(v);
    const int wta = wrong(v), smoothed = wrong(aggregate_paths(v, scale, 2 * scale, 8));
    MESSAGE("wrong labels: winner-take-all " << wta << ", smoothed " << smoothed);
    CHECK(wta > rows * cols / 5);
    CHECK(smoothed < wta / 4);
    CHECK_THROWS_AS(aggregate_paths(v, 0.2, 0.1, 8), InvalidInput);
    CHECK_THROWS_AS(aggregate_paths(v, 0.1, 0.2, 3), InvalidInput);
}

TEST_CASE("cost_well_depth is the mean of median minus minimum") {
    // Two pixels; costs (3, 1, 2) and (5, 5, 4): upper-middle medians 2 and 5.
    std::vector<Plane> c(3, Plane(1, 2));
    c[0] << 3, 5;
    c[1] << 1, 5;
    c[2] << 2, 4;
    CHECK(cost_well_depth(c) == doctest::Approx(((2 - 1) + (5 - 4)) / 2.0));
    const Plane label = (Plane(1, 2) << 1, 0).finished();
    const Plane conf = label_confidence(c, label);
    CHECK(conf(0, 0) == doctest::Approx(0.5));  // (2 - 1) / 2
    CHECK(conf(0, 1) == 0.0);                   // (5 - 5) / 5
}
