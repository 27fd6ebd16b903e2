#include "decode/calibrate/calibrated_psf.hpp"

#include <cmath>

#include "core/units/number_format.hpp"
#include "decode/calibrate/profile_table.hpp"

namespace pinmask::calibrate {

Plane fitted_kernel(const ForwardFit& fit, const Mask& mask, int half) {
    const ProfileTable q(mask.camera, fit.family, fit.side_m, half + 1.0);
    Plane k(2 * half + 1, 2 * half + 1);
    for (int r = -half; r <= half; ++r)
        for (int c = -half; c <= half; ++c) k(r + half, c + half) = q.value(r) * q.value(c);
    const double s = k.sum();
    if (s > 0) k /= s;
    return k;
}

CalibratedPsfs calibrated_psfs(int rows, int cols, const ForwardFit& fit, const Mask& mask,
                               double tol) {
    CalibratedPsfs out;
    out.full_frame = fitted_psf(fit, mask, rows, cols);

    const int n = mask.pattern.n;
    const double c = std::cos(fit.lattice.rotation_rad), sn = std::sin(fit.lattice.rotation_rad);
    const double px = fit.lattice.pitch_x_px, py = fit.lattice.pitch_y_px;
    const int nc = static_cast<int>(std::lround(n * px * c));
    const int nr = static_cast<int>(std::lround(n * py * c));
    out.period_drift_px = std::max({std::abs(n * px * c - nc), std::abs(n * px * sn),
                                    std::abs(n * py * c - nr), std::abs(n * py * sn)});
    if (out.period_drift_px > tol || nc < 1 || nr < 1) {
        out.period_reason = "the lattice drifts " + format_number(out.period_drift_px) +
                            " px from whole pixels over one period (tolerance " +
                            format_number(tol) +
                            " px): no cyclic PSF on a pixel torus; use the full-frame PSF";
        return out;
    }
    out.period_reason = "period " + std::to_string(nc) + " x " + std::to_string(nr) +
                        " px, drift " + format_number(out.period_drift_px) + " px";
    // The kernel wrapped onto the torus: a window as wide as the period (its tails fold).
    const int half = std::max(nr, nc) / 2;
    const ProfileTable q(mask.camera, fit.family, fit.side_m, half + 1.0);
    Plane per = Plane::Zero(nr, nc);
    for (const Cell& cell : mask.pattern.pinholes) {
        double g = 0.0;
        int copies = 0;
        for (const auto& f : fit.pinholes) {
            if (!f.in_frame || f.mask_cell.row % n != cell.row || f.mask_cell.col % n != cell.col)
                continue;
            ++copies;
            if (!f.missing) g += std::max(f.gain, 0.0);
        }
        g = copies > 0 ? g / copies : fit.median_gain;
        if (g <= 0) continue;
        const double x = (cell.col + 0.5) * nc / n - 0.5, y = (cell.row + 0.5) * nr / n - 0.5;
        const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
        for (int dr = -half; dr <= half + 1; ++dr)
            for (int dc = -half; dc <= half + 1; ++dc) {
                const int r = yi + dr, cc = xi + dc;
                const double v = q.value(r - y) * q.value(cc - x);
                per(((r % nr) + nr) % nr, ((cc % nc) + nc) % nc) += g * v;
            }
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
