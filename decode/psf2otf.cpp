#include "decode/psf2otf.hpp"

#include <string>

#include "core/error.hpp"
#include "core/fft.hpp"

namespace pinmask {

Plane psf_to_origin(const Plane& psf, int rows, int cols) {
    if (psf.rows() < 1 || psf.cols() < 1) {
        throw invalid_field("psf", "empty", "the PSF needs at least one pixel");
    }
    if (psf.rows() > rows || psf.cols() > cols) {
        throw invalid_field("psf", std::to_string(psf.rows()) + " x " + std::to_string(psf.cols()),
                            "must not be larger than the working size " + std::to_string(rows) +
                                " x " + std::to_string(cols));
    }
    const Eigen::Index cr = psf.rows() / 2, cc = psf.cols() / 2;
    Plane out = Plane::Zero(rows, cols);
    for (Eigen::Index r = 0; r < psf.rows(); ++r) {
        const Eigen::Index rr = (r - cr + rows) % rows;
        for (Eigen::Index c = 0; c < psf.cols(); ++c) {
            out(rr, (c - cc + cols) % cols) = psf(r, c);
        }
    }
    return out;
}

ComplexPlane psf2otf(const Plane& psf, int rows, int cols) {
    return Fft2(rows, cols).forward(psf_to_origin(psf, rows, cols));
}

}  // namespace pinmask
