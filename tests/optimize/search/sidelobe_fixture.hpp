// Shared fixture of the search tests (tests/optimize/search/test_search.cpp,
// test_island_search.cpp): a cheap objective with a known optimum structure and a rejection sampler
// of legal patterns.
#pragma once

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "design/pattern/pattern.hpp"
#include "optimize/search/pattern_state.hpp"
#include "optimize/search/search.hpp"

namespace pinmask::test {

// The maximum autocorrelation sidelobe plus a small integrated-sidelobe term (ties broken
// smoothly).
class SidelobeObjective : public SearchObjective {
  public:
    double evaluate(const PatternState& s) const override {
        const auto t = terms(s);
        return t.at("max_sidelobe") + 1e-3 * t.at("integrated_sidelobe");
    }
    std::map<std::string, double> terms(const PatternState& s) const override {
        const auto& r = s.autocorrelation();
        int max_side = 0;
        double isl = 0.0;
        for (std::size_t i = 1; i < r.size(); ++i) {
            max_side = std::max(max_side, r[i]);
            isl += static_cast<double>(r[i]) * r[i];
        }
        return {{"max_sidelobe", max_side}, {"integrated_sidelobe", isl}};
    }
};

// Rejection sampler for tests: uniform cells, keep those that respect the rule and keep-out.
inline Pattern sample_pattern(std::mt19937_64& rng, int n, int holes, double spacing,
                              const std::vector<Cell>& keep_out = {}) {
    std::uniform_int_distribution<int> cell(0, n - 1);
    Pattern p;
    p.n = n;
    p.min_spacing_cells = spacing;
    while (static_cast<int>(p.pinholes.size()) < holes) {
        const Cell c{cell(rng), cell(rng)};
        if (std::find(keep_out.begin(), keep_out.end(), c) != keep_out.end()) continue;
        bool ok = true;
        for (const Cell& q : p.pinholes)
            ok = ok && torus_distance_cells(c, q, n) >= spacing - kSpacingTolerance;
        if (ok) p.pinholes.push_back(c);
    }
    return p;
}

}  // namespace pinmask::test
