#include "design/pattern/exclusion_grid.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>

namespace pinmask {

std::vector<ExclusionRow> exclusion_rows(double min_spacing_cells) {
    const double limit = min_spacing_cells - kSpacingTolerance;
    if (!(limit > 0.0)) return {{0, 0}};
    const double limit2 = limit * limit;
    const int reach = static_cast<int>(std::ceil(limit));
    std::vector<ExclusionRow> out;
    for (int dr = -reach; dr <= reach; ++dr) {
        const double rest = limit2 - static_cast<double>(dr) * dr;
        if (dr != 0 && !(rest > 0.0)) continue;
        // Largest w with dr^2 + w^2 < limit2, from the square root then corrected exactly.
        int w = rest > 0.0 ? static_cast<int>(std::sqrt(rest)) : 0;
        while (w > 0 && static_cast<double>(w) * w >= rest) --w;
        while (static_cast<double>(w + 1) * (w + 1) < rest) ++w;
        out.push_back({dr, w});
    }
    return out;
}

std::size_t count_spacing_violations(const Pattern& p) {
    const double limit = p.min_spacing_cells - kSpacingTolerance;
    const int reach = limit > 0.0 ? static_cast<int>(std::ceil(limit)) : 0;
    // On tori too small for every offset within reach to be the unique shortest one (and when
    // pinholes clash with their own copies), the listing function's bookkeeping is needed.
    if (p.n < 2 * reach + 1) return spacing_violations(p).size();
    const auto occ = occupancy(p);
    const int n = p.n;
    std::size_t count = 0;
    for (const ExclusionRow& row : exclusion_rows(p.min_spacing_cells)) {
        // Offsets in the half plane dr > 0 or (dr = 0, dc > 0): every close pair once.
        if (row.dr < 0) continue;
        const int dc_lo = row.dr == 0 ? 1 : -row.half_width;
        for (const Cell& c : p.pinholes) {
            int r = c.row + row.dr;
            r -= r >= n ? n : 0;
            const std::uint8_t* line = &occ[static_cast<std::size_t>(r) * n];
            for (int dc = dc_lo; dc <= row.half_width; ++dc) {
                int k = c.col + dc;
                k += k < 0 ? n : (k >= n ? -n : 0);
                count += line[k];
            }
        }
    }
    return count;
}

ExclusionGrid::ExclusionGrid(int n, double min_spacing_cells, Index index)
    : n_(n),
      rows_(exclusion_rows(min_spacing_cells)),
      free_count_(static_cast<std::size_t>(n) * n) {
    const std::size_t cells = free_count_;
    const std::size_t nwords = (cells + 63) / 64;
    words_.assign(nwords, ~std::uint64_t{0});
    if (cells % 64) words_.back() = (std::uint64_t{1} << (cells % 64)) - 1;
    if (index == Index::kRank) {
        // Linear-time Fenwick construction: each node passes its sum to its parent.
        fenwick_.assign(nwords + 1, 0);
        for (std::size_t w = 0; w < nwords; ++w) {
            fenwick_[w + 1] += static_cast<std::uint32_t>(std::popcount(words_[w]));
            const std::size_t parent = (w + 1) + ((w + 1) & (~(w + 1) + 1));
            if (parent <= nwords) fenwick_[parent] += fenwick_[w + 1];
        }
    }
}

void ExclusionGrid::fenwick_add(std::size_t word, std::uint32_t minus) {
    for (std::size_t i = word + 1; i < fenwick_.size(); i += i & (~i + 1)) fenwick_[i] -= minus;
}

std::size_t ExclusionGrid::nth_free(std::size_t r) const {
    assert(!fenwick_.empty() && r < free_count_);
    const std::size_t nwords = fenwick_.size() - 1;
    std::size_t pos = 0;
    for (std::size_t step = std::bit_floor(nwords); step; step >>= 1) {
        if (pos + step <= nwords && fenwick_[pos + step] <= r) {
            pos += step;
            r -= fenwick_[pos];
        }
    }
    // pos = the word holding the r-th free cell; select its r-th set bit.
    std::uint64_t w = words_[pos];
    for (std::size_t k = 0; k < r; ++k) w &= w - 1;
    return pos * 64 + static_cast<std::size_t>(std::countr_zero(w));
}

void ExclusionGrid::place(Cell c) {
    const bool ranked = !fenwick_.empty();
    for (const ExclusionRow& row : rows_) {
        // |dr|, half_width <= ceil(s) <= n, so one correction wraps them; a row segment wider
        // than the torus is the whole row, visited once.
        int r = c.row + row.dr;
        r += r < 0 ? n_ : (r >= n_ ? -n_ : 0);
        const int width = std::min(2 * row.half_width + 1, n_);
        int k = c.col - row.half_width;
        k += k < 0 ? n_ : 0;
        if (width == n_) k = 0;
        const std::size_t base = static_cast<std::size_t>(r) * n_;
        std::size_t pending_word = 0;
        std::uint32_t pending = 0;  // cells blocked in pending_word, not yet in the Fenwick tree
        for (int step = 0; step < width; ++step, k = k + 1 == n_ ? 0 : k + 1) {
            const std::size_t i = base + static_cast<std::size_t>(k);
            const std::uint64_t bit = std::uint64_t{1} << (i & 63);
            std::uint64_t& word = words_[i >> 6];
            if (!(word & bit)) continue;
            word &= ~bit;
            --free_count_;
            if (!ranked) continue;
            if (pending && pending_word != (i >> 6)) {
                fenwick_add(pending_word, pending);
                pending = 0;
            }
            pending_word = i >> 6;
            ++pending;
        }
        if (pending) fenwick_add(pending_word, pending);
    }
}

}  // namespace pinmask
