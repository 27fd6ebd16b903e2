#include "calibrate/calibrated_psf.hpp"

#include <cmath>
#include <map>

#include "calibrate/subpixel.hpp"

namespace pinmask::calibrate {

CalibratedPsfs calibrated_psfs(int rows, int cols, const KernelEstimate& kernel,
                               const std::vector<Spot>& spots, const PinholeMatch& match,
                               const LatticeFit& fit, const Pattern& pattern, double tol) {
    CalibratedPsfs out;
    const double h = kernel.half_px;
    const double mf = match.median_flux > 0 ? match.median_flux : 1.0;
    out.full_frame = Plane::Zero(rows, cols);
    std::map<int, int> merged_count;
    for (const auto& rec : match.pinholes)
        if (rec.state == PinholeState::kMerged) ++merged_count[rec.spot];
    for (const auto& rec : match.pinholes) {
        Eigen::Vector2d p = rec.predicted;
        double w = 0.0;
        if (rec.state == PinholeState::kFound) {
            const Eigen::Vector2d res = rec.measured - rec.predicted;
            if (res.norm() > kResidualSignificance * fit.residual_rms_px) p = rec.measured;
            w = rec.gain;
        } else if (rec.state == PinholeState::kMerged) {
            w = spots[rec.spot].flux / mf / merged_count[rec.spot];
        }
        if (w > 0) add_kernel(out.full_frame, kernel.values, h, h, p.y(), p.x(), w);
    }
    for (int k : match.extra_spots)
        if (spots[k].flux > 0)
            add_kernel(out.full_frame, kernel.values, h, h, spots[k].y, spots[k].x,
                       spots[k].flux / mf);
    const double s = out.full_frame.sum();
    if (s > 0) out.full_frame /= s;

    // One period.
    const int n = pattern.n;
    const double c = std::cos(fit.rotation_rad), sn = std::sin(fit.rotation_rad);
    const int nc = static_cast<int>(std::lround(n * fit.pitch_x_px * c));
    const int nr = static_cast<int>(std::lround(n * fit.pitch_y_px * c));
    out.period_drift_px =
        std::max({std::abs(n * fit.pitch_x_px * c - nc), std::abs(n * fit.pitch_x_px * sn),
                  std::abs(n * fit.pitch_y_px * c - nr), std::abs(n * fit.pitch_y_px * sn)});
    if (out.period_drift_px > tol || nc < 1 || nr < 1) {
        out.period_reason = "the lattice drifts " + std::to_string(out.period_drift_px) +
                            " px from whole pixels over one period (tolerance " +
                            std::to_string(tol) +
                            " px): no cyclic PSF on a pixel torus; use the full-frame PSF";
        return out;
    }
    out.period_reason = "period " + std::to_string(nc) + " x " + std::to_string(nr) +
                        " px, drift " + std::to_string(out.period_drift_px) + " px";
    Plane per = Plane::Zero(nr, nc);
    for (const Cell& cell : pattern.pinholes) {
        double g = 0.0;
        int copies = 0;
        for (const auto& rec : match.pinholes) {
            if (rec.mask_cell.row % n != cell.row || rec.mask_cell.col % n != cell.col) continue;
            ++copies;
            if (rec.state == PinholeState::kFound) g += rec.gain;
            if (rec.state == PinholeState::kMerged)
                g += spots[rec.spot].flux / mf / merged_count[rec.spot];
        }
        g = copies > 0 ? g / copies : 1.0;
        if (g <= 0) continue;
        const double x = (cell.col + 0.5) * nc / n - 0.5, y = (cell.row + 0.5) * nr / n - 0.5;
        add_kernel(per, kernel.values, h, h, y, x, g, true);
    }
    if (per.sum() > 0) {
        per /= per.sum();
        out.period = per;
    } else {
        out.period_reason = "every pinhole copy in frame is missing: no cyclic PSF";
    }
    return out;
}

}  // namespace pinmask::calibrate
