#include "decode/solvers/solver_common.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

void validate_iterative_options(const IterativeOptions& o) {
    if (o.max_iterations < 0) {
        throw invalid_field("max_iterations", std::to_string(o.max_iterations), "must be >= 0");
    }
    if (!(o.tolerance >= 0.0) || !std::isfinite(o.tolerance)) {
        throw invalid_field("tolerance", std::to_string(o.tolerance), "must be finite and >= 0");
    }
}

void check_warm_start(const Plane& w, const ConvGeometry& g) {
    if (w.rows() != g.work_rows || w.cols() != g.work_cols) {
        throw invalid_field("warm_start",
                            std::to_string(w.rows()) + " x " + std::to_string(w.cols()),
                            "must have the working size " + std::to_string(g.work_rows) + " x " +
                                std::to_string(g.work_cols));
    }
    if (!is_all_finite(w)) throw invalid_field("warm_start", "non-finite values", "must be finite");
}

double relative_change(const Plane& a, const Plane& b) {
    const double diff = std::sqrt((a - b).square().sum());
    const double norm = std::sqrt(a.square().sum());
    if (diff == 0.0) return 0.0;
    return norm > 0.0 ? diff / norm : std::numeric_limits<double>::infinity();
}

}  // namespace pinmask
