#include "calibrate/registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "calibrate/spots.hpp"
#include "core/error.hpp"
#include "core/field_names.hpp"

namespace pinmask::calibrate {

Eigen::Vector2d LatticeFit::position(double i, double j) const {
    const double c = std::cos(rotation_rad), s = std::sin(rotation_rad);
    return {x0 + pitch_x_px * c * i - pitch_y_px * s * j,
            y0 + pitch_x_px * s * i + pitch_y_px * c * j};
}

Eigen::Vector2d LatticeFit::indices(double x, double y) const {
    const double c = std::cos(rotation_rad), s = std::sin(rotation_rad);
    const double dx = x - x0, dy = y - y0;
    return {(c * dx + s * dy) / pitch_x_px, (-s * dx + c * dy) / pitch_y_px};
}

namespace {

constexpr double kPi = std::numbers::pi;

struct Site {
    Eigen::Vector2d p;
    double i = 0, j = 0;
};

// Sites of the points whose indices under `fit` are within max_offset of integers.
std::vector<Site> sites_on(const LatticeFit& fit, const std::vector<Eigen::Vector2d>& pts,
                           double max_offset) {
    std::vector<Site> out;
    for (const auto& p : pts) {
        const Eigen::Vector2d u = fit.indices(p.x(), p.y());
        const double i = std::round(u.x()), j = std::round(u.y());
        if (std::abs(u.x() - i) <= max_offset && std::abs(u.y() - j) <= max_offset)
            out.push_back({p, i, j});
    }
    return out;
}

// Gauss-Newton on (x0, y0, t, px, py); returns the covariance-scaled fit.
LatticeFit least_squares(LatticeFit f, const std::vector<Site>& sites) {
    const int m = static_cast<int>(sites.size());
    Eigen::MatrixXd jac(2 * m, 5);
    Eigen::VectorXd res(2 * m);
    auto evaluate = [&](const LatticeFit& g) {
        const double c = std::cos(g.rotation_rad), s = std::sin(g.rotation_rad);
        for (int k = 0; k < m; ++k) {
            const double i = sites[k].i, j = sites[k].j;
            const Eigen::Vector2d q = g.position(i, j);
            res(2 * k) = sites[k].p.x() - q.x();
            res(2 * k + 1) = sites[k].p.y() - q.y();
            jac.row(2 * k) << 1, 0, -g.pitch_x_px * s * i - g.pitch_y_px * c * j, c * i, -s * j;
            jac.row(2 * k + 1) << 0, 1, g.pitch_x_px * c * i - g.pitch_y_px * s * j, s * i, c * j;
        }
    };
    for (int it = 0; it < 20; ++it) {
        evaluate(f);
        const Eigen::VectorXd step = jac.colPivHouseholderQr().solve(res);
        f.x0 += step(0);
        f.y0 += step(1);
        f.rotation_rad += step(2);
        f.pitch_x_px += step(3);
        f.pitch_y_px += step(4);
        if (step.cwiseAbs().maxCoeff() < 1e-12) break;
    }
    evaluate(f);
    const double rss = res.squaredNorm();
    const double s2 = m > 3 ? rss / (2.0 * m - 5.0) : 0.0;
    const Eigen::MatrixXd cov = s2 * (jac.transpose() * jac).inverse();
    f.x0_sigma = std::sqrt(std::max(cov(0, 0), 0.0));
    f.y0_sigma = std::sqrt(std::max(cov(1, 1), 0.0));
    f.rotation_sigma_rad = std::sqrt(std::max(cov(2, 2), 0.0));
    f.pitch_x_sigma_px = std::sqrt(std::max(cov(3, 3), 0.0));
    f.pitch_y_sigma_px = std::sqrt(std::max(cov(4, 4), 0.0));
    f.residual_rms_px = std::sqrt(rss / std::max(m, 1));
    f.spots_used = m;
    return f;
}

}  // namespace

LatticeFit fit_lattice(const std::vector<Eigen::Vector2d>& pts, const RegistrationOptions& o) {
    const double p0 = o.nominal_pitch_px;
    const std::string searched = "rotation within +-" + std::to_string(o.max_rotation_deg) +
                                 " deg (" + field_ref("max_rotation_deg") + "), pitch " +
                                 std::to_string(p0) + " px +-" +
                                 std::to_string(100.0 * o.pitch_range) + " %";
    if (pts.size() < 3) {
        throw InvalidInput("calibrate: " + std::to_string(pts.size()) +
                           " spots cannot fix a lattice (at least 3 needed)");
    }
    // Neighbour vectors.
    const double reach = kNeighbourCells * p0 * (1.0 + o.pitch_range);
    std::vector<Eigen::Vector2d> vecs;
    for (std::size_t a = 0; a < pts.size(); ++a)
        for (std::size_t b = a + 1; b < pts.size(); ++b) {
            const Eigen::Vector2d v = pts[b] - pts[a];
            if (v.norm() <= reach && v.norm() > 0.5 * p0) vecs.push_back(v);
        }
    if (vecs.empty())
        throw InvalidInput("calibrate: no two spots lie within a few cells: " + searched);
    // Coarse grid: steps small enough that the phase error over kNeighbourCells cells stays below
    // ~0.15 rad (0.25 deg and 0.25 % of pitch).
    const double max_t = o.max_rotation_deg * kPi / 180.0;
    const double t_step = 0.25 * kPi / 180.0, s_step = 0.0025;
    double best = -1e300, best_t = 0.0, best_s = p0;
    for (double t = -max_t; t <= max_t + 1e-12; t += t_step) {
        const double c = std::cos(t), sn = std::sin(t);
        for (double f = -o.pitch_range; f <= o.pitch_range + 1e-12; f += s_step) {
            const double inv = 1.0 / (p0 * (1.0 + f));
            double score = 0.0;
            for (const auto& v : vecs) {
                score += std::cos(2 * kPi * (c * v.x() + sn * v.y()) * inv) +
                         std::cos(2 * kPi * (-sn * v.x() + c * v.y()) * inv);
            }
            if (score > best) {
                best = score;
                best_t = t;
                best_s = p0 * (1.0 + f);
            }
        }
    }
    // Reference: the point nearest the centroid of all points.
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    const auto ref = *std::min_element(pts.begin(), pts.end(), [&](const auto& a, const auto& b) {
        return (a - mean).squaredNorm() < (b - mean).squaredNorm();
    });
    LatticeFit fit;
    fit.x0 = ref.x();
    fit.y0 = ref.y();
    fit.rotation_rad = best_t;
    fit.pitch_x_px = fit.pitch_y_px = best_s;
    // Grow from the coarse lattice: loose tolerance first, then the configured one.
    for (double tol : {0.35, o.max_index_offset, o.max_index_offset}) {
        std::vector<Site> sites = sites_on(fit, pts, tol);
        if (sites.size() < 3) {
            throw InvalidInput(
                "calibrate: the spots do not form a lattice in the range searched (" + searched +
                "); the rotation may exceed " + field_ref("max_rotation_deg"));
        }
        fit = least_squares(fit, sites);
        // Drop outliers and refit.
        std::vector<double> r;
        for (const auto& s : sites) r.push_back((s.p - fit.position(s.i, s.j)).norm());
        const double cut = kOutlierSigmas * std::max(1.4826 * median_of(r), 1e-3);
        std::vector<Site> kept;
        for (std::size_t k = 0; k < sites.size(); ++k)
            if (r[k] <= cut) kept.push_back(sites[k]);
        if (kept.size() >= 3 && kept.size() < sites.size()) fit = least_squares(fit, kept);
    }
    return fit;
}

}  // namespace pinmask::calibrate
