// Incremental state of a pattern under single-pinhole moves, for search (docs/design.md section 2):
//   P^(k, l) = sum_j w^(k r_j + l c_j),  w = exp(-2 pi i / n)      (n x n DFT of the 0/1 pattern)
//   R(d)     = #{(i, j) : p_j - p_i = d (mod n)}                    (torus autocorrelation)
// Moving one pinhole from a to b changes P^ by two separable plane waves, w^(k b_r + l b_c) -
// w^(k a_r + l a_c): O(n^2), no FFT. It changes R by at most 4 (K - 1) entries: O(K). An exclusion
// count per cell (how many pinholes lie closer than the spacing rule) makes "is this move legal"
// O(1) and its update O(s^2), s = ceil(min_spacing_cells).
// Adding or removing one pinhole (search --holes A..B) changes P^ by one plane wave
// (O(n^2)) and R by 2 (K - 1) + 1 entries (O(K)); the spacing rule is the same torus rule, so it
// holds across tile seams (the mask is the pattern repeated).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/pattern.hpp"

namespace pinmask {

class PatternState {
  public:
    // The pattern must satisfy validate(p) (spacing rule included).
    explicit PatternState(const Pattern& p);

    const Pattern& pattern() const { return pattern_; }
    int n() const { return pattern_.n; }
    int holes() const { return static_cast<int>(pattern_.pinholes.size()); }

    // Full n x n spectrum P^ (row-major, unnormalised forward DFT convention of core/fft/fft.hpp).
    const ComplexPlane& spectrum() const { return spectrum_; }
    // Autocorrelation counts R(dr, dc) as an n x n array, R(0, 0) = K.
    const std::vector<int>& autocorrelation() const { return autocorr_; }
    int autocorrelation_at(int dr, int dc) const;

    bool is_open(Cell c) const { return occupied_[index(c)] != 0; }
    // True when pinhole `j` may move to `to`: `to` is empty and no other pinhole is closer than
    // the spacing rule on the torus.
    bool is_legal_move(int j, Cell to) const;
    // Moves pinhole j to `to` (must be legal; asserted in debug builds) and updates everything.
    // Staying put (to == current cell) is not a legal move.
    void move(int j, Cell to);

    // True when a pinhole may be added at `c`: inside the grid, empty, and no pinhole closer than
    // the spacing rule on the torus.
    bool can_add(Cell c) const;
    // Adds a pinhole at `c` (must satisfy can_add; asserted in debug builds) as the last one.
    void add(Cell c);
    // Removes pinhole j (K must stay >= 1; asserted); the last pinhole takes index j.
    void remove(int j);

    // Recomputes spectrum and autocorrelation from scratch (design/psf/psf pattern_spectrum and
    // optimize/metrics/autocorrelation), for tests and to resynchronise accumulated round-off.
    void recompute();

  private:
    std::size_t index(Cell c) const { return static_cast<std::size_t>(c.row) * pattern_.n + c.col; }
    void add_exclusion(Cell c, int delta);
    void update_spectrum(Cell from, Cell to);
    void add_wave(Cell at, double sign);  // P^ += sign w^(k at.r + l at.c)
    void add_autocorrelation(int j, Cell at, int delta);
    // Exclusion that pinhole at `c` alone contributes to cell `t` (0 or 1).
    bool excludes(Cell c, Cell t) const;

    Pattern pattern_;
    std::vector<std::uint8_t> occupied_;
    std::vector<int> exclusion_;  // per cell: pinholes closer than the rule (itself included)
    std::vector<Cell> stencil_;   // offsets closer than the rule, (0, 0) included
    std::vector<std::complex<double>> twiddle_;  // w^m, m = 0 .. n-1
    ComplexPlane spectrum_;
    std::vector<int> autocorr_;
    std::vector<std::complex<double>> row_wave_, col_wave_, row_old_, col_old_;  // scratch
};

}  // namespace pinmask
