#include "optimize/metrics/nsr_tuning.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

ScalarMinimum golden_section_minimise(const std::function<double(double)>& f, double lo, double hi,
                                      double tolerance) {
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
        throw InvalidInput("golden-section bracket [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]: must be finite with lo < hi");
    }
    if (!(tolerance > 0.0)) {
        throw invalid_field("tolerance", std::to_string(tolerance), "must be > 0");
    }
    const double inv_phi = (std::sqrt(5.0) - 1.0) / 2.0;  // 0.618...
    ScalarMinimum best{lo, std::numeric_limits<double>::infinity(), 0};
    auto eval = [&](double x) {
        double v = f(x);
        if (std::isnan(v)) v = std::numeric_limits<double>::infinity();
        ++best.evaluations;
        if (v < best.value) {
            best.x = x;
            best.value = v;
        }
        return v;
    };
    eval(lo);
    eval(hi);
    double a = lo, b = hi;
    double c = b - inv_phi * (b - a), d = a + inv_phi * (b - a);
    double fc = eval(c), fd = eval(d);
    while (b - a > tolerance) {
        if (fc <= fd) {  // minimum in [a, d]
            b = d;
            d = c;
            fd = fc;
            c = b - inv_phi * (b - a);
            fc = eval(c);
        } else {  // minimum in [c, b]
            a = c;
            c = d;
            fc = fd;
            d = a + inv_phi * (b - a);
            fd = eval(d);
        }
    }
    return best;
}

ScalarMinimum tune_log_weight(const std::function<double(double)>& error) {
    ScalarMinimum m = golden_section_minimise([&](double t) { return error(std::pow(10.0, t)); },
                                              kTuneMinLog10, kTuneMaxLog10, kTuneToleranceLog10);
    m.x = std::pow(10.0, m.x);
    return m;
}

}  // namespace pinmask
