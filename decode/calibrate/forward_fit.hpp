// Registration as a fit of the forward model to the whole point-source capture.
// Coordinates: index coordinates (x = column, y = row, pixel centres on integers). Rotation t is
// counter-clockwise on screen with rows running down (the sense of scipy.ndimage.rotate with a
// positive angle): the mask's column axis points along (cos t, -sin t), its row axis along
// (sin t, cos t). Mask cell (R, C) of the tiled mask (R, C from 0) images its pinhole at
//   x = x0 + px cos(t) C + py sin(t) R,   y = y0 - px sin(t) C + py cos(t) R,
// so (x0, y0) is the spot centre of cell (0, 0), px and py the pitches along the mask's column
// and row axes (pixels of the capture).
// Model of the frame (dark frame already subtracted):
//   m = B + L F + sum over the tiled mask's open cells k of g_k K_d(x - x_k, y - y_k)
// where K_d(u, v) = q_d(u') q_d(v') is the pinhole kernel of the mask's family (box, fraunhofer,
// fresnel; decode/calibrate/profile_table) at the pinhole side d = s d_design, (u', v') the offsets
// along the mask's axes; g_k the flux of pinhole k (its gain), L the leak per pixel of opaque film,
// F the film's area (the tiled mask's cells imaged by the same lattice without the open cells'
// clear pinholes, anti-aliased over one pixel), B the background. Each spot is evaluated in a
// window of
// +- core_cells cells, or wider to hold the kernel's central lobes (out to v = 2N + 2); the
// diffraction tails beyond it (sinc^2 falls as 1/v^2) enter as a halo, the same kernel's tail
// with each spot at its own position on a grid along the mask's axes (the separable kernel makes
// all the tails one matrix product there; pixels read the grid by 6-point Lagrange
// interpolation), made from the current
// parameters before each round and held fixed inside it (a fixed point: the tail carries a few
// percent of the energy). Solver: Levenberg-Marquardt on (x0, y0, t, px, py, s, g_1..g_G, L, B)
// with the analytic Jacobian (s by a forward difference of the table), weights 1 / var with the
// Poisson-Gaussian variance var = alpha max(m, 0) + beta fitted to the residuals (first an
// unweighted fit, then two weighted rounds). Covariance: the inverse Fisher information (J^T W
// J)^-1 scaled by the reduced chi^2 (1 when the noise model holds). The leak is non-negative: a
// negative estimate is refitted with L = 0. When the footprint covers the frame, L and B are one
// constant: with a dark frame subtracted B is held at 0 and L fitted, without one L is held at 0
// (not measured).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask::calibrate {

struct LatticeStart {
    double x0 = 0.0, y0 = 0.0;  // spot centre of mask cell (0, 0)
    double rotation_rad = 0.0;  // counter-clockwise on screen
    double pitch_x_px = 0.0, pitch_y_px = 0.0;
};

struct ForwardFitOptions {
    double core_cells = 2.5;  // half width of each spot's window for diffraction kernels (cells)
    // The halo reaches out to this per-axis energy of the kernel, at most halo_cap_px. Light
    // beyond it is in the capture but not in the model, and the leak and background take it up:
    // sinc^2 keeps ~2 / (pi^2 a x) of its energy beyond x pixels, so a reach of 512 px left
    // 1.1 % of every spot (NIR camera) against a film leak of 0.1 % of a pinhole per cell, and
    // the optical density came out 0.1 low (docs/calibration.md). The halo is one matrix product
    // over the frame whatever its reach; a longer reach adds only the sites beyond the frame.
    double halo_energy = 0.99999;
    int halo_cap_px = 4096;
    int max_iterations = 40;  // Levenberg-Marquardt iterations per round
    // A pinhole is missing when its gain's upper one-sided bound at this false-alarm rate
    // (z sigma above the estimate) is below half the median gain of the in-frame pinholes: an open
    // pinhole passing at least half the median flux is called missing with probability below it.
    double missing_false_alarm = 1e-4;
    // The frame's background is known to be 0 (a dark frame was subtracted): used when the
    // mask's footprint covers the frame, where leak and background cannot be told apart.
    bool dark_subtracted = false;
    // Pixels outside the footprint needed to tell the leak from the background: at least this
    // many and this fraction of the frame.
    int min_outside_px = 500;
    double min_outside_fraction = 0.02;
    // Called after every Levenberg-Marquardt iteration with the iterations so far and the round's
    // cap (progress for the faces; may be empty).
    std::function<void(int iterations, int cap)> on_iteration;
};

struct FittedPinhole {
    Cell mask_cell;                       // (R, C) over the tiled mask
    double x = 0.0, y = 0.0;              // fitted spot centre
    double gain = 0.0, gain_sigma = 0.0;  // flux (counts), its standard error
    bool in_frame = false;  // centre at least half a pitch inside the frame: classified
    bool missing = false;
};

struct ForwardFit {
    LatticeStart lattice;
    double side_scale = 1.0;  // d / d_design
    double side_m = 0.0;
    KernelModel family = KernelModel::kBox;
    // Standard errors of (x0, y0, t, px, py, s).
    double x0_sigma = 0.0, y0_sigma = 0.0, rotation_sigma_rad = 0.0, pitch_x_sigma_px = 0.0,
           pitch_y_sigma_px = 0.0, side_scale_sigma = 0.0;
    std::vector<FittedPinhole> pinholes;
    double median_gain = 0.0;
    double leak = 0.0, leak_sigma = 0.0;  // counts per pixel, >= 0
    bool leak_at_bound = false;           // the unconstrained estimate was negative
    // False when the footprint covers the frame and no dark frame fixes the background: the
    // leak is then held at 0 and not measured (leak_sigma NaN).
    bool leak_measured = true;
    double background = 0.0, background_sigma = 0.0;
    double noise_alpha = 0.0, noise_beta = 0.0;  // var = alpha max(m, 0) + beta
    double chi2_reduced = 0.0;
    // Share of the signal's energy sum (m - B)^2 left in the residual beyond the noise model:
    // max(0, sum r^2 - sum var) / sum (m - B)^2 (0 when the model explains the capture).
    double unexplained = 0.0;
    double missing_z = 0.0;  // the z of missing_false_alarm
    int iterations = 0;
    bool converged = false;
    Plane model;  // the fitted model of the frame (with background and leak)
};

// The binning of the fit of a capture with cells pitch_px wide on a rows x cols frame (1: none;
// see fit_forward_model).
int first_pass_binning(double pitch_px, int rows, int cols);
// The frame's b x b pixel sums (rows / b x cols / b; a remainder of rows or columns is dropped).
// Binned pixel (i, j) covers pixels b i .. b i + b - 1: index coordinate x of the capture is
// (x + 1/2) / b - 1/2 in the binned frame.
Plane bin_frame(const Plane& frame, int b);
LatticeStart to_binned(const LatticeStart& lattice, int b);
LatticeStart from_binned(const LatticeStart& lattice, int b);

// Fits the model above, started from `start`. A capture whose short side is at least 1024 px
// with cells at least 16 px wide is fitted binned b x b (b = floor(pitch / 8)): parameters,
// standard errors and missing pinholes are the binned fit's in the capture's pixels; the model,
// noise model, chi^2 and unexplained share are made at full resolution. `mask.camera` must carry
// the capture's pixel pitch (binning applied). Throws InvalidInput when the start puts no open
// cell's spot in the frame, RuntimeFailure when the normal equations are singular.
ForwardFit fit_forward_model(const Plane& frame, const Mask& mask, const LatticeStart& start,
                             const ForwardFitOptions& options = {});

// The fitted spots alone (every open cell not missing, gain max(g, 0), full kernel with its
// tails) on a rows x cols frame, normalised to sum 1: the calibrated full-frame PSF.
Plane fitted_psf(const ForwardFit& fit, const Mask& mask, int rows, int cols,
                 const ForwardFitOptions& options = {});

}  // namespace pinmask::calibrate
