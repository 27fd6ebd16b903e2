#include "decode/solvers/tikhonov.hpp"

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "decode/solvers/gradient.hpp"
#include "decode/solvers/psf2otf.hpp"

namespace pinmask {

WienerFilter make_tikhonov_filter(const Plane& psf, int rows, int cols, double lambda,
                                  TikhonovRegulariser regulariser) {
    if (!(lambda >= 0.0) || !std::isfinite(lambda)) {
        throw invalid_field("lambda", std::to_string(lambda), "must be finite and >= 0");
    }
    return make_tikhonov_filter_from_otf(psf2otf(psf, rows, cols), rows, cols, lambda, regulariser);
}

Plane tikhonov_symbol(int rows, int cols, TikhonovRegulariser regulariser) {
    return regulariser == TikhonovRegulariser::kGradient ? gradient_gram_symbol(rows, cols)
                                                         : Plane::Ones(rows, cols / 2 + 1);
}

WienerFilter make_tikhonov_filter_from_otf(const ComplexPlane& h, int rows, int cols, double lambda,
                                           TikhonovRegulariser regulariser) {
    if (!(lambda >= 0.0) || !std::isfinite(lambda)) {
        throw invalid_field("lambda", std::to_string(lambda), "must be finite and >= 0");
    }
    if (rows < 1 || cols < 1 || h.rows() != rows || h.cols() != cols / 2 + 1) {
        throw invalid_field(
            "otf", std::to_string(h.rows()) + " x " + std::to_string(h.cols()),
            "must be the half spectrum of " + std::to_string(rows) + " x " + std::to_string(cols));
    }
    const Plane l2 = tikhonov_symbol(rows, cols, regulariser);
    ComplexPlane g(h.rows(), h.cols());
    for (Eigen::Index i = 0; i < h.size(); ++i) {
        const double denom = std::norm(h.data()[i]) + lambda * l2.data()[i];
        g.data()[i] = denom > 0.0 ? std::conj(h.data()[i]) / denom : 0.0;
    }
    return WienerFilter::from_half_spectrum(std::move(g), rows, cols);
}

double tikhonov_penalty(const Plane& x, double lambda, TikhonovRegulariser regulariser) {
    if (regulariser == TikhonovRegulariser::kIdentity) return lambda * x.square().sum();
    Plane d_r, d_c;
    gradient(x, d_r, d_c);
    return lambda * (d_r.square().sum() + d_c.square().sum());
}

}  // namespace pinmask
