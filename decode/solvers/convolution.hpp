// Convolution models of decode/: the forward operator A and its adjoint A^T.
//
// Notation: a the PSF (pr x pc), H = psf2otf(a) on the working grid, x the scene on the working
// grid (work_rows x work_cols), p the capture (capture_rows x capture_cols), C the crop of the
// working grid to the capture window and C^T its adjoint (zero padding).
// - cyclic: the working grid is the capture grid, A x = real(ifft2(H .* fft2(x))) (circular
//   convolution over one period, the paper's model), C = identity.
// - linear: the working grid is FFT-friendly (2^a 3^b 5^c 7^d) and at least capture + psf - 1
//   per axis, the capture window is centred in it (crop_row = floor((work - capture) / 2)) and
//   A x = C (H x). Because the grid is that large, the window never sees wrapped-around light:
//   every x pixel reaching the window is distinct, so A is a linear (zero-padded) convolution
//   followed by a crop. The reported image is the centre crop C x, of capture size.
#pragma once

#include "core/fft/fft.hpp"
#include "core/image/image.hpp"
#include "decode/capture/decoder.hpp"

namespace pinmask {

// Where the capture sits in the working grid of a convolution model.
struct ConvGeometry {
    ConvModel model = ConvModel::kCyclic;
    int capture_rows = 0, capture_cols = 0;
    int work_rows = 0, work_cols = 0;  // grid of x and of the FFTs
    int crop_row = 0, crop_col = 0;    // top-left corner of the capture window in the grid
};

// Smallest n' >= n (n >= 1) whose prime factors are all in {2, 3, 5, 7}.
int next_fft_size(int n);

// The working grid of `model` for a capture and PSF size. Throws InvalidInput for empty sizes,
// a PSF larger than the capture (cyclic), or ResourceLimit for a grid beyond the memory bound.
ConvGeometry make_conv_geometry(ConvModel model, int capture_rows, int capture_cols, int psf_rows,
                                int psf_cols);

// C: the capture window of a working-grid plane.
Plane crop_to_capture(const ConvGeometry& g, const Plane& work);
// C^T: a capture-size plane zero-padded into the working grid.
Plane pad_to_work(const ConvGeometry& g, const Plane& capture);

// The forward operator A of a (PSF, geometry) pair with its transfer function precomputed.
class ConvolutionOperator {
  public:
    // Throws InvalidInput when the PSF is empty or larger than the working grid.
    ConvolutionOperator(const Plane& psf, const ConvGeometry& geometry);

    const ConvGeometry& geometry() const { return geometry_; }
    const Fft2& fft() const { return fft_; }
    // H on the working grid, half spectrum work_rows x (work_cols / 2 + 1).
    const ComplexPlane& otf() const { return otf_; }
    // max |H| = ||H x|| operator norm; ||A|| <= this (equal for the cyclic model).
    double otf_max_abs() const { return otf_max_abs_; }

    // A x: working grid -> capture size.
    Plane apply(const Plane& x) const;
    // A^T y: capture size -> working grid.
    Plane adjoint(const Plane& y) const;
    // H x and H^T v on the working grid (no crop).
    Plane convolve(const Plane& x) const;
    Plane correlate(const Plane& v) const;

  private:
    ConvGeometry geometry_;
    Fft2 fft_;
    ComplexPlane otf_;
    double otf_max_abs_ = 0.0;
};

}  // namespace pinmask
