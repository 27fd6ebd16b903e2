#include "optimize/search/pattern_state.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

#include "core/fft/fft.hpp"
#include "design/psf/psf.hpp"
#include "optimize/metrics/autocorrelation.hpp"

namespace pinmask {
namespace {

int wrap(int v, int n) { return ((v % n) + n) % n; }

}  // namespace

PatternState::PatternState(const Pattern& p) : pattern_(p) {
    validate(p);
    const int n = p.n;
    occupied_ = occupancy(p);
    exclusion_.assign(static_cast<std::size_t>(n) * n, 0);
    // Offsets (dr, dc) with torus-reduced distance below the rule, each cell of the torus once.
    const int reach = std::min(static_cast<int>(std::ceil(p.min_spacing_cells)), n / 2);
    for (int dr = -reach; dr <= reach; ++dr) {
        for (int dc = -reach; dc <= reach; ++dc) {
            const Cell off{wrap(dr, n), wrap(dc, n)};
            bool seen = false;
            for (const Cell& s : stencil_) seen = seen || (s == off);
            if (seen) continue;
            if (torus_distance_cells({0, 0}, off, n) < p.min_spacing_cells - kSpacingTolerance) {
                stencil_.push_back(off);
            }
        }
    }
    // A cell holds one pinhole, so (0, 0) is excluded even for spacing 0.
    bool has_origin = false;
    for (const Cell& s : stencil_) has_origin = has_origin || (s == Cell{0, 0});
    if (!has_origin) stencil_.push_back({0, 0});
    for (const Cell& c : p.pinholes) add_exclusion(c, +1);
    twiddle_.resize(n);
    for (int m = 0; m < n; ++m) twiddle_[m] = std::polar(1.0, -2.0 * std::numbers::pi * m / n);
    row_wave_.resize(n);
    col_wave_.resize(n);
    row_old_.resize(n);
    col_old_.resize(n);
    recompute();
}

void PatternState::recompute() {
    spectrum_ = pattern_spectrum(pattern_);
    autocorr_ = autocorrelation_from_spectrum(spectrum_);
}

int PatternState::autocorrelation_at(int dr, int dc) const {
    return autocorr_[static_cast<std::size_t>(wrap(dr, n())) * n() + wrap(dc, n())];
}

void PatternState::add_exclusion(Cell c, int delta) {
    const int n = pattern_.n;
    for (const Cell& s : stencil_) {
        int r = c.row + s.row, q = c.col + s.col;  // stencil offsets are in [0, n)
        if (r >= n) r -= n;
        if (q >= n) q -= n;
        exclusion_[static_cast<std::size_t>(r) * n + q] += delta;
    }
}

bool PatternState::excludes(Cell c, Cell t) const {
    const int n = pattern_.n;
    const Cell off{wrap(t.row - c.row, n), wrap(t.col - c.col, n)};
    for (const Cell& s : stencil_) {
        if (s == off) return true;
    }
    return false;
}

bool PatternState::is_legal_move(int j, Cell to) const {
    if (to.row < 0 || to.row >= n() || to.col < 0 || to.col >= n()) return false;
    if (occupied_[index(to)]) return false;
    const int e = exclusion_[index(to)];
    if (e == 0) return true;
    if (e > 1) return false;
    // Exactly one pinhole excludes `to`: legal only if it is the one that moves.
    return excludes(pattern_.pinholes[static_cast<std::size_t>(j)], to);
}

void PatternState::update_spectrum(Cell from, Cell to) {
    // P^(k, l) += w^(k to.r) w^(l to.c) - w^(k from.r) w^(l from.c), one fused pass over the
    // n x n array with explicit real arithmetic (std::complex multiplication goes through the
    // NaN-safe library routine without -ffast-math). Twiddle indices advance by addition.
    const int n = pattern_.n;
    const std::complex<double>* w = twiddle_.data();
    int ia = 0, ib = 0, ja = 0, jb = 0;
    for (int k = 0; k < n; ++k) {
        row_wave_[k] = w[ib];  // w^(k to.r)
        col_wave_[k] = w[jb];  // w^(k to.c)
        row_old_[k] = w[ia];   // w^(k from.r)
        col_old_[k] = w[ja];   // w^(k from.c)
        ib += to.row;
        if (ib >= n) ib -= n;
        jb += to.col;
        if (jb >= n) jb -= n;
        ia += from.row;
        if (ia >= n) ia -= n;
        ja += from.col;
        if (ja >= n) ja -= n;
    }
    const double* cb = reinterpret_cast<const double*>(col_wave_.data());
    const double* ca = reinterpret_cast<const double*>(col_old_.data());
    for (int k = 0; k < n; ++k) {
        double* row = reinterpret_cast<double*>(&spectrum_(k, 0));
        const double br = row_wave_[k].real(), bi = row_wave_[k].imag();
        const double ar = row_old_[k].real(), ai = row_old_[k].imag();
        for (int l = 0; l < n; ++l) {
            const double xr = cb[2 * l], xi = cb[2 * l + 1];
            const double yr = ca[2 * l], yi = ca[2 * l + 1];
            row[2 * l] += (br * xr - bi * xi) - (ar * yr - ai * yi);
            row[2 * l + 1] += (br * xi + bi * xr) - (ar * yi + ai * yr);
        }
    }
}

void PatternState::add_wave(Cell at, double sign) {
    const int n = pattern_.n;
    const std::complex<double>* w = twiddle_.data();
    int ib = 0, jb = 0;
    for (int k = 0; k < n; ++k) {
        row_wave_[k] = sign * w[ib];
        col_wave_[k] = w[jb];
        ib += at.row;
        if (ib >= n) ib -= n;
        jb += at.col;
        if (jb >= n) jb -= n;
    }
    const double* cb = reinterpret_cast<const double*>(col_wave_.data());
    for (int k = 0; k < n; ++k) {
        double* row = reinterpret_cast<double*>(&spectrum_(k, 0));
        const double br = row_wave_[k].real(), bi = row_wave_[k].imag();
        for (int l = 0; l < n; ++l) {
            const double xr = cb[2 * l], xi = cb[2 * l + 1];
            row[2 * l] += br * xr - bi * xi;
            row[2 * l + 1] += br * xi + bi * xr;
        }
    }
}

void PatternState::add_autocorrelation(int j, Cell at, int delta) {
    const int n = pattern_.n;
    int* r = autocorr_.data();
    for (int i = 0; i < holes(); ++i) {
        if (i == j) continue;
        const Cell q = pattern_.pinholes[static_cast<std::size_t>(i)];
        int dr = at.row - q.row, dc = at.col - q.col;  // in (-n, n)
        if (dr < 0) dr += n;
        if (dc < 0) dc += n;
        const int mr = dr == 0 ? 0 : n - dr, mc = dc == 0 ? 0 : n - dc;
        r[dr * n + dc] += delta;
        r[mr * n + mc] += delta;
    }
}

void PatternState::move(int j, Cell to) {
    assert(is_legal_move(j, to));
    Cell& slot = pattern_.pinholes[static_cast<std::size_t>(j)];
    const Cell from = slot;
    add_autocorrelation(j, from, -1);
    add_exclusion(from, -1);
    occupied_[index(from)] = 0;
    slot = to;
    add_autocorrelation(j, to, +1);
    add_exclusion(to, +1);
    occupied_[index(to)] = 1;
    update_spectrum(from, to);
}

bool PatternState::can_add(Cell c) const {
    if (c.row < 0 || c.row >= n() || c.col < 0 || c.col >= n()) return false;
    return occupied_[index(c)] == 0 && exclusion_[index(c)] == 0;
}

void PatternState::add(Cell c) {
    assert(can_add(c));
    pattern_.pinholes.push_back(c);
    const int j = holes() - 1;
    add_autocorrelation(j, c, +1);
    autocorr_[0] += 1;
    add_exclusion(c, +1);
    occupied_[index(c)] = 1;
    add_wave(c, +1.0);
}

void PatternState::remove(int j) {
    assert(holes() > 1 && j >= 0 && j < holes());
    const Cell at = pattern_.pinholes[static_cast<std::size_t>(j)];
    add_autocorrelation(j, at, -1);
    autocorr_[0] -= 1;
    add_exclusion(at, -1);
    occupied_[index(at)] = 0;
    pattern_.pinholes[static_cast<std::size_t>(j)] = pattern_.pinholes.back();
    pattern_.pinholes.pop_back();
    add_wave(at, -1.0);
}

}  // namespace pinmask
