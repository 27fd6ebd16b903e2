#include "optimize/search/depth_term.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <thread>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/psf/psf_exact.hpp"
#include "optimize/search/pattern_state.hpp"

namespace pinmask {
namespace {

constexpr int kStride = 2;  // residue classes per axis: spots of one class are 2 pitches apart

// The tiled cell index (along one axis) of the nearest spot of residue class `a` (basic index
// mod kStride) to the continuous cell coordinate x, within 0 .. nt - 1; -1 when none.
int nearest_in_class(double x, int a, int n, int nt) {
    const int c = static_cast<int>(std::floor(x));
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = c - kStride - 1; i <= c + kStride + 1; ++i) {
        if (i < 0 || i >= nt || (i % n) % kStride != a) continue;
        const double d = std::abs(i + 0.5 - x);
        if (d < best_d) best_d = d, best = i;
    }
    if (best >= 0) return best;
    // Beyond the mask's edge: the outermost cell of the class on that side.
    for (int i = x < 0 ? 0 : nt - 1; i >= 0 && i < nt; i += x < 0 ? 1 : -1)
        if ((i % n) % kStride == a) return i;
    return -1;
}

}  // namespace

DepthCellTable::DepthCellTable(const Mask& tmpl, const NoiseModel& noise, const DepthRange& range,
                               int threads) {
    if (noise.kind != NoiseKind::kPhoton) {
        throw InvalidInput(field_ref("weights.depth") +
                           " > 0: the depth term's Cramer-Rao bound needs the photon model (" +
                           field_ref("photons") + "), not Gaussian noise at an SNR");
    }
    const DepthFisherOptions fo = depth_fisher_noise(noise, 1);  // photons: one pinhole's
    const double r2 = fo.read_noise_e * fo.read_noise_e;
    n_ = tmpl.pattern.n;
    const int ntr = n_ * tmpl.pattern.tiles_rows, ntc = n_ * tmpl.pattern.tiles_cols;
    const int rows = tmpl.camera.sensor_rows, cols = tmpl.camera.sensor_cols;
    u_ = depth_samples(tmpl, range);
    const int classes = std::min(kStride, n_);
    info_.assign(u_.size(), std::vector<double>(static_cast<std::size_t>(n_) * n_, 0.0));
    // One job per distance and residue class; each writes only its own class's cells.
    const auto job = [&](std::size_t k, int a, int b) {
        const double u = u_[k];
        std::vector<double>& info = info_[k];
        const SpotCentre c00 = exact_spot_centre(tmpl, u, rows, cols, 0, 0);
        const SpotCentre c11 = exact_spot_centre(tmpl, u, rows, cols, 1, 1);
        const double pitch_r = c11.row - c00.row, pitch_c = c11.col - c00.col;
        Mask m = tmpl;
        m.pattern.pinholes.clear();
        for (int i = a; i < n_; i += kStride)
            for (int j = b; j < n_; j += kStride) m.pattern.pinholes.push_back({i, j});
        // Each spot weighs 1/K' in the PSF: photons_per_pinhole K' electrons in all give each
        // spot photons_per_pinhole.
        const double photons = fo.photons * static_cast<double>(m.pattern.pinholes.size());
        const DepthSlope s = depth_slope(m, u, rows, cols);
        std::vector<int> row_cell(rows), col_cell(cols);
        for (int r = 0; r < rows; ++r)
            row_cell[r] = nearest_in_class((r + 0.5 - c00.row) / pitch_r + 0.5, a, n_, ntr);
        for (int q = 0; q < cols; ++q)
            col_cell[q] = nearest_in_class((q + 0.5 - c00.col) / pitch_c + 0.5, b, n_, ntc);
        for (int r = 0; r < rows; ++r) {
            if (row_cell[r] < 0) continue;
            for (int q = 0; q < cols; ++q) {
                if (col_cell[q] < 0) continue;
                const double var = photons * s.psf(r, q) + r2;
                if (!(var > 0.0)) continue;
                const double d = photons * s.slope(r, q);
                info[static_cast<std::size_t>(row_cell[r] % n_) * n_ + col_cell[q] % n_] +=
                    d * d / var;
            }
        }
    };
    const int jobs = static_cast<int>(u_.size()) * classes * classes;
    std::atomic<int> next{0};
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(jobs));
    const auto worker = [&] {
        for (int j; (j = next.fetch_add(1)) < jobs;) {
            try {
                job(static_cast<std::size_t>(j / (classes * classes)), (j / classes) % classes,
                    j % classes);
            } catch (...) {
                errors[static_cast<std::size_t>(j)] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::clamp(threads, 1, jobs); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);  // the first job's error, whatever the thread count
}

double DepthCellTable::crb_rel(const std::vector<Cell>& pinholes) const {
    double worst = 0.0;
    for (std::size_t k = 0; k < u_.size(); ++k) {
        double info = 0.0;
        for (const Cell& c : pinholes)
            info += info_[k][static_cast<std::size_t>(c.row) * n_ + c.col];
        worst = std::max(
            worst, info > 0.0 ? u_[k] / std::sqrt(info) : std::numeric_limits<double>::infinity());
    }
    return worst;
}

DepthTermObjective::DepthTermObjective(std::unique_ptr<SearchObjective> inner,
                                       std::shared_ptr<const DepthCellTable> table, double weight)
    : inner_(std::move(inner)), table_(std::move(table)), weight_(weight) {
    if (!inner_ || !table_) throw InvalidInput("the depth term needs an objective and a table");
}

double DepthTermObjective::depth_db(const PatternState& s) const {
    return 20.0 * std::log10(table_->crb_rel(s.pattern().pinholes));
}

double DepthTermObjective::evaluate(const PatternState& s) const {
    return inner_->evaluate(s) + weight_ * depth_db(s);
}

std::map<std::string, double> DepthTermObjective::terms(const PatternState& s) const {
    std::map<std::string, double> out = inner_->terms(s);
    out["depth_crb_rel"] = table_->crb_rel(s.pattern().pinholes);
    out["depth_crb_rel_db"] = depth_db(s);
    out["objective"] = evaluate(s);
    return out;
}

}  // namespace pinmask
