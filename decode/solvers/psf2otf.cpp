#include "decode/solvers/psf2otf.hpp"

#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"

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
    // psf(r, c) moves to ((r - cr) mod rows, (c - cc) mod cols): four block copies (the PSF's
    // quadrants around its centre), which cannot overlap as the PSF fits the working size.
    const Eigen::Index pr = psf.rows(), pc = psf.cols(), cr = pr / 2, cc = pc / 2;
    Plane out = Plane::Zero(rows, cols);
    out.block(0, 0, pr - cr, pc - cc) = psf.block(cr, cc, pr - cr, pc - cc);
    out.block(0, cols - cc, pr - cr, cc) = psf.block(cr, 0, pr - cr, cc);
    out.block(rows - cr, 0, cr, pc - cc) = psf.block(0, cc, cr, pc - cc);
    out.block(rows - cr, cols - cc, cr, cc) = psf.block(0, 0, cr, cc);
    return out;
}

ComplexPlane psf2otf(const Plane& psf, int rows, int cols) {
    return Fft2(rows, cols).forward(psf_to_origin(psf, rows, cols));
}

}  // namespace pinmask
