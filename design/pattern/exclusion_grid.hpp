// Which cells of an n x n torus can still take a pinhole under the spacing rule
// (design/pattern/pattern.hpp: centres at least min_spacing_cells apart, Euclidean, on the torus).
// Cells are indexed row * n + col. Used by the random sparse family and the lattice placements.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "design/pattern/pattern.hpp"

namespace pinmask {

// One row of the exclusion disc: the offsets (dr, dc), |dc| <= half_width, are closer than the
// rule (d < s - kSpacingTolerance). (0, 0) is always included: a cell takes one pinhole.
struct ExclusionRow {
    int dr = 0;
    int half_width = 0;
};

// The rows of the disc, dr ascending; |dr|, half_width <= ceil(s). O(s) memory.
std::vector<ExclusionRow> exclusion_rows(double min_spacing_cells);

// Number of pinhole pairs closer than the rule, equal to spacing_violations(p).size() but
// without listing them (a MURA of order 4093 has 1.7e7 such pairs): O(K s^2) time, n^2 bytes.
// Pinholes must be inside the grid and distinct (see validate()).
std::size_t count_spacing_violations(const Pattern& p);

class ExclusionGrid {
  public:
    // kRank keeps a Fenwick tree of free cells per 64-cell word so that nth_free() is
    // O(log n); it costs O(log n) per blocked cell.
    enum class Index { kNone, kRank };

    // Every cell free. 1 <= n and n >= ceil(s - kSpacingTolerance) (the caller refuses smaller
    // tori: a pinhole would violate against its own periodic copy). Memory n^2 / 8 bytes
    // (+ n^2 / 16 with kRank).
    ExclusionGrid(int n, double min_spacing_cells, Index index = Index::kNone);

    int n() const { return n_; }
    bool is_free(std::size_t i) const { return (words_[i >> 6] >> (i & 63)) & 1U; }
    bool is_free(Cell c) const { return is_free(index_of(c)); }
    std::size_t free_count() const { return free_count_; }
    std::size_t index_of(Cell c) const { return static_cast<std::size_t>(c.row) * n_ + c.col; }
    Cell cell_of(std::size_t i) const {
        return {static_cast<int>(i / n_), static_cast<int>(i % n_)};
    }

    // The index of the r-th free cell in index order, 0 <= r < free_count(). Needs kRank.
    std::size_t nth_free(std::size_t r) const;

    // Blocks c and every cell closer than the rule to c. O(s^2) (times log n with kRank).
    void place(Cell c);

  private:
    void fenwick_add(std::size_t word, std::uint32_t minus);

    int n_;
    std::vector<ExclusionRow> rows_;
    std::vector<std::uint64_t> words_;    // bit set = cell free
    std::vector<std::uint32_t> fenwick_;  // 1-based Fenwick tree of free cells per word
    std::size_t free_count_;
};

}  // namespace pinmask
