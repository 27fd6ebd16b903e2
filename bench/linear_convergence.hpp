// Time to quality on the linear (zero-padded, cropped) model: simulated full-frame captures with
// a ground truth, and the TV-L2 iterations after which the estimate's PSNR stays within a band of
// its converged PSNR.
//
// A problem: a PSF, a scene on the working grid (the light that reaches the sensor window comes
// from a region capture + PSF - 1 wide, so the scene fills the whole grid), the capture
// C (h (*) scene) + Gaussian noise at snr_db (relative to the clean capture's rms), seeded. The
// capture is rendered by a direct spatial-domain convolution here (independent of the solver's
// FFT model), over the window only.
// Quality: PSNR (peak 1, the scenes' range) of the capture window of the estimate against the
// scene's: the part of the scene the sensor sees in full.
// Cases (linear_convergence_cases), each at `scale` = 1 (full size) or smaller for tests:
//   paper-full-sensor   the paper camera (preset mask, seed 1) at its design distance 6 m, the
//                       exact-geometry PSF cut to its support, the whole 480 x 720 sensor
//   refocused-2m        the same camera with the object at 2 m (pitch 8.63 px, not a whole
//                       number), decoded with the exact PSF at 2 m
//   diffusercam         the DiffuserCam tutorial's measured PSF (when the file is given),
//                       background-subtracted and box-downsampled 4x (300 x 400) as the
//                       tutorial does; a natural scene
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/solvers/tv_l2.hpp"

namespace pinmask {

struct LinearProblem {
    std::string name;
    Plane psf;
    Plane scene;    // working grid
    Plane capture;  // capture window
    ConvGeometry geometry;
    double lambda = 0.0;  // the TV weight used for it (capture units)
};

// Renders the capture of `scene` (working grid of make_conv_geometry(kLinear, rows, cols, psf))
// with Gaussian noise at snr_db; the scene is resized to the working grid by the caller.
LinearProblem make_linear_problem(const std::string& name, const Plane& psf, int capture_rows,
                                  int capture_cols, const Plane& scene_window_source, double snr_db,
                                  double lambda_relative, std::uint64_t seed);

// The cases above at `scale` (1 = full size; 0.5 halves every pixel count per axis: PSF
// downsampled, sensor window halved). diffusercam_psf_path empty: that case is left out.
std::vector<LinearProblem> linear_convergence_cases(double scale,
                                                    const std::string& diffusercam_psf_path);

struct IterationsToQuality {
    int iterations = 0;    // the first k after which every PSNR stays within the band
    bool reached = false;  // false when max_iterations did not get there
    double converged_psnr_db = 0.0;
    double psnr_at_iterations_db = 0.0;
    std::vector<double> psnr_db;  // per iteration 1..max_iterations
};

// Runs TV-L2 (options: lambda, nonnegative, precision, rho) reference_iterations iterations
// (tolerance 0) for the converged PSNR, then max_iterations with the PSNR of every iterate.
IterationsToQuality tv_l2_iterations_to_quality(const LinearProblem& problem, TvL2Options options,
                                                double within_db, int max_iterations,
                                                int reference_iterations);

}  // namespace pinmask
