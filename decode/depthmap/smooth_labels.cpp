#include "decode/depthmap/smooth_labels.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

// One path direction (dr, dc): adds L_r - C to s. vol and s hold K values per pixel, pixels in
// row-major order. The pixels are visited so that each one's predecessor (i - dr, j - dc) comes
// first: forward raster order for dr > 0 or (dr = 0, dc > 0), backward otherwise.
void add_path(const std::vector<double>& vol, std::vector<double>& s, std::vector<double>& l,
              Eigen::Index rows, Eigen::Index cols, std::size_t k_count, int dr, int dc, double p1,
              double p2) {
    const bool forward = dr > 0 || (dr == 0 && dc > 0);
    const Eigen::Index n = rows * cols;
    for (Eigen::Index step = 0; step < n; ++step) {
        const Eigen::Index p = forward ? step : n - 1 - step;
        const Eigen::Index i = p / cols, j = p % cols;
        const Eigen::Index qi = i - dr, qj = j - dc;
        const double* c = &vol[std::size_t(p) * k_count];
        double* lp = &l[std::size_t(p) * k_count];
        if (qi < 0 || qi >= rows || qj < 0 || qj >= cols) {
            std::copy(c, c + k_count, lp);  // the path starts here: no message
            continue;
        }
        const double* lq = &l[std::size_t(qi * cols + qj) * k_count];
        const double m = *std::min_element(lq, lq + k_count);
        double* sp = &s[std::size_t(p) * k_count];
        for (std::size_t d = 0; d < k_count; ++d) {
            double best = std::min(lq[d], m + p2);
            if (d > 0) best = std::min(best, lq[d - 1] + p1);
            if (d + 1 < k_count) best = std::min(best, lq[d + 1] + p1);
            lp[d] = c[d] + best - m;
            sp[d] += best - m;  // L_r - C
        }
    }
}

}  // namespace

std::vector<Plane> aggregate_paths(const std::vector<Plane>& costs, double p1, double p2,
                                   int paths) {
    if (costs.empty()) throw invalid_field("planes", "0", "need at least one cost plane");
    for (std::size_t k = 1; k < costs.size(); ++k) {
        if (costs[k].rows() != costs[0].rows() || costs[k].cols() != costs[0].cols())
            throw invalid_field("planes", std::to_string(k), "cost planes differ in size");
    }
    if (!(p1 >= 0.0) || !(p2 >= p1) || !std::isfinite(p2))
        throw invalid_field("smooth", std::to_string(p1) + ", " + std::to_string(p2),
                            "penalties must be finite with 0 <= p1 <= p2");
    if (paths != 2 && paths != 4 && paths != 8)
        throw invalid_field("paths", std::to_string(paths), "must be 2, 4 or 8");
    const Eigen::Index rows = costs[0].rows(), cols = costs[0].cols();
    const std::size_t k_count = costs.size(), n = std::size_t(rows * cols);
    std::vector<double> vol(n * k_count);
    for (std::size_t k = 0; k < k_count; ++k)
        for (std::size_t p = 0; p < n; ++p) vol[p * k_count + k] = costs[k].data()[p];
    std::vector<double> s = vol, l(n * k_count);
    static constexpr int kDirections[8][2] = {{0, 1}, {0, -1},  {1, 0},  {-1, 0},
                                              {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
    for (int r = 0; r < paths; ++r)
        add_path(vol, s, l, rows, cols, k_count, kDirections[r][0], kDirections[r][1], p1, p2);
    std::vector<Plane> out(k_count, Plane(rows, cols));
    for (std::size_t k = 0; k < k_count; ++k)
        for (std::size_t p = 0; p < n; ++p) out[k].data()[p] = s[p * k_count + k];
    return out;
}

double cost_well_depth(const std::vector<Plane>& costs) {
    if (costs.empty()) return 0.0;
    const std::size_t k_count = costs.size();
    const Eigen::Index n = costs[0].size();
    std::vector<double> c(k_count);
    double sum = 0.0;
    for (Eigen::Index p = 0; p < n; ++p) {
        for (std::size_t k = 0; k < k_count; ++k) c[k] = costs[k].data()[p];
        const double lo = *std::min_element(c.begin(), c.end());
        std::nth_element(c.begin(), c.begin() + k_count / 2, c.end());
        sum += c[k_count / 2] - lo;
    }
    return n > 0 ? sum / double(n) : 0.0;
}

}  // namespace pinmask
