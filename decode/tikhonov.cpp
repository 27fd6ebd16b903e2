#include "decode/tikhonov.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "decode/gradient.hpp"
#include "decode/psf2otf.hpp"

namespace pinmask {

WienerFilter make_tikhonov_filter(const Plane& psf, int rows, int cols, double lambda,
                                  TikhonovRegulariser regulariser) {
    if (!(lambda >= 0.0) || !std::isfinite(lambda)) {
        throw invalid_field("lambda", std::to_string(lambda), "must be finite and >= 0");
    }
    const ComplexPlane h = psf2otf(psf, rows, cols);
    const Plane l2 = regulariser == TikhonovRegulariser::kGradient
                         ? gradient_gram_symbol(rows, cols)
                         : Plane::Ones(h.rows(), h.cols());
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
