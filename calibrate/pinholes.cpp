#include "calibrate/pinholes.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

#include "calibrate/spots.hpp"

namespace pinmask::calibrate {

PinholeMatch match_pinholes(const std::vector<Spot>& spots, const LatticeFit& fit,
                            const Pattern& pattern, int frame_rows, int frame_cols,
                            double max_index_offset) {
    const int n = pattern.n;
    const int mr = n * pattern.tiles_rows, mc = n * pattern.tiles_cols;
    std::vector<std::uint8_t> open(static_cast<std::size_t>(n) * n, 0);
    for (const Cell& c : pattern.pinholes) open[static_cast<std::size_t>(c.row) * n + c.col] = 1;
    const auto is_open = [&](int r, int c) {
        return r >= 0 && c >= 0 && r < mr && c < mc &&
               open[static_cast<std::size_t>(r % n) * n + (c % n)] != 0;
    };
    const double margin = 0.5 * std::max(fit.pitch_x_px, fit.pitch_y_px) + 1.0;
    const auto in_frame = [&](const Eigen::Vector2d& p) {
        return p.x() >= margin && p.y() >= margin && p.x() <= frame_cols - 1 - margin &&
               p.y() <= frame_rows - 1 - margin;
    };
    // Spots on lattice sites (in frame), with their integer indices.
    struct OnSite {
        int spot, i, j;
    };
    std::vector<OnSite> on_site;
    std::vector<int> off_site;
    for (int k = 0; k < static_cast<int>(spots.size()); ++k) {
        const Eigen::Vector2d p(spots[k].x, spots[k].y);
        if (!in_frame(p)) continue;
        const Eigen::Vector2d u = fit.indices(p.x(), p.y());
        const double i = std::round(u.x()), j = std::round(u.y());
        if (std::abs(u.x() - i) <= max_index_offset && std::abs(u.y() - j) <= max_index_offset)
            on_site.push_back({k, static_cast<int>(i), static_cast<int>(j)});
        else
            off_site.push_back(k);
    }
    PinholeMatch m;
    if (on_site.empty()) return m;
    int imin = INT_MAX, imax = INT_MIN, jmin = INT_MAX, jmax = INT_MIN;
    for (const auto& s : on_site) {
        imin = std::min(imin, s.i);
        imax = std::max(imax, s.i);
        jmin = std::min(jmin, s.j);
        jmax = std::max(jmax, s.j);
    }
    // Occupied lattice sites, for O(1) look-ups.
    const int gw = imax - imin + 1, gh = jmax - jmin + 1;
    std::vector<std::uint8_t> occupied(static_cast<std::size_t>(gw) * gh, 0);
    for (const auto& s : on_site)
        occupied[static_cast<std::size_t>(s.j - jmin) * gw + (s.i - imin)] = 1;
    const auto has_spot = [&](int i, int j) {
        return i >= imin && i <= imax && j >= jmin && j <= jmax &&
               occupied[static_cast<std::size_t>(j - jmin) * gw + (i - imin)] != 0;
    };
    // Open cells and their predicted positions depend on the offset; search every offset that
    // keeps at least one spot on the mask.
    double best = -1e300;
    for (int orow = -jmax; orow <= mr - 1 - jmin; ++orow) {
        for (int ocol = -imax; ocol <= mc - 1 - imin; ++ocol) {
            int matched = 0, wrong = 0;
            for (const auto& s : on_site) (is_open(s.j + orow, s.i + ocol) ? matched : wrong)++;
            if (matched == 0) continue;
            int absent = 0;
            for (int t = 0; t < pattern.tiles_rows * pattern.tiles_cols; ++t)
                for (const Cell& c : pattern.pinholes) {
                    const int r = c.row + n * (t / pattern.tiles_cols);
                    const int col = c.col + n * (t % pattern.tiles_cols);
                    if (!in_frame(fit.position(col - ocol, r - orow))) continue;
                    if (!has_spot(col - ocol, r - orow)) ++absent;
                }
            const double score = matched - wrong - 0.5 * absent;
            if (score > best) {
                best = score;
                m.offset_row = orow;
                m.offset_col = ocol;
            }
        }
    }
    // Records for every open cell in frame.
    std::vector<double> fluxes, areas;
    for (int r = 0; r < mr; ++r)
        for (int c = 0; c < mc; ++c) {
            if (!is_open(r, c)) continue;
            PinholeRecord rec;
            rec.mask_cell = {r, c};
            rec.predicted = fit.position(c - m.offset_col, r - m.offset_row);
            rec.measured = rec.predicted;
            if (!in_frame(rec.predicted)) continue;
            for (const auto& s : on_site) {
                if (s.j + m.offset_row != r || s.i + m.offset_col != c) continue;
                if (rec.spot < 0 || spots[s.spot].flux > spots[rec.spot].flux) rec.spot = s.spot;
            }
            if (rec.spot >= 0) {
                rec.state = PinholeState::kFound;
                rec.measured = {spots[rec.spot].x, spots[rec.spot].y};
                fluxes.push_back(spots[rec.spot].flux);
                areas.push_back(spots[rec.spot].area_px);
            }
            m.pinholes.push_back(rec);
        }
    // Spots on sites that did not become a pinhole's spot are extra.
    std::vector<std::uint8_t> used(spots.size(), 0);
    for (const auto& rec : m.pinholes)
        if (rec.spot >= 0) used[rec.spot] = 1;
    for (const auto& s : on_site)
        if (!used[s.spot]) off_site.push_back(s.spot);
    std::sort(off_site.begin(), off_site.end());
    // Merged: an off-site spot whose grown box holds two or more spot-less predicted centres.
    for (int k : off_site) {
        const Spot& sp = spots[k];
        std::vector<PinholeRecord*> inside;
        for (auto& rec : m.pinholes) {
            if (rec.state != PinholeState::kMissing) continue;
            if (rec.predicted.x() >= sp.col0 - 1 && rec.predicted.x() <= sp.col1 + 1 &&
                rec.predicted.y() >= sp.row0 - 1 && rec.predicted.y() <= sp.row1 + 1)
                inside.push_back(&rec);
        }
        if (inside.size() >= 2) {
            for (auto* rec : inside) {
                rec->state = PinholeState::kMerged;
                rec->spot = k;
            }
        } else {
            m.extra_spots.push_back(k);
        }
    }
    m.median_flux = median_of(fluxes);
    m.median_area_px = median_of(areas);
    for (auto& rec : m.pinholes) {
        if (rec.state != PinholeState::kFound) continue;
        rec.gain = m.median_flux > 0 ? spots[rec.spot].flux / m.median_flux : 0.0;
        rec.oversized = spots[rec.spot].area_px > kOversizedArea * m.median_area_px;
    }
    return m;
}

}  // namespace pinmask::calibrate
