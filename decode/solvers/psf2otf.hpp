// psf2otf: the PSF's transfer function on a working grid, with MATLAB deconvwnr/psf2otf centring.
//
// Notation: a the PSF (pr x pc), R x C the working grid. The PSF is zero-padded to R x C and
// circularly shifted so that its central element, 0-based index (floor(pr / 2), floor(pc / 2)),
// lands at the origin (0, 0). The OTF is the forward DFT (core/fft/fft.hpp conventions) of that
// shifted plane, kept as the real-to-complex half spectrum R x (C / 2 + 1).
#pragma once

#include "core/image/image.hpp"

namespace pinmask {

// The PSF zero-padded to rows x cols with its central element moved to the origin. Throws
// InvalidInput when the PSF is empty or larger than rows x cols in either dimension.
Plane psf_to_origin(const Plane& psf, int rows, int cols);

// Half spectrum (rows x (cols / 2 + 1)) of psf_to_origin(psf, rows, cols).
ComplexPlane psf2otf(const Plane& psf, int rows, int cols);

}  // namespace pinmask
