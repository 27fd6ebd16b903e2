// The calibration pipeline: a point-source capture through the whole mask (several periods,
// K x tiles spots) -> measured geometry, per-pinhole gains, leak, background, kernel, calibrated
// PSF. Steps (one concept per file): dark frame -> spots (decode/calibrate/spots: the refusals of
// unusable captures) -> the lattice's start from the capture's Fourier transform
// (decode/calibrate/lattice_fft) -> the fit of the forward model
// to the whole capture (decode/calibrate/forward_fit): geometry, kernel side, gains, leak,
// background and their standard errors -> missing pinholes from the gains, extra light from the
// residual -> PSFs from the fitted model (decode/calibrate/calibrated_psf) -> the fitted kernel
// against the design's kernel models (decode/calibrate/kernel_fit). Coordinates: index coordinates
// (x = column, y = row, pixel centres on integers). Rotation: counter-clockwise on screen with rows
// running down positive (scipy.ndimage.rotate's sense).
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/calibrate/calibrated_psf.hpp"
#include "decode/calibrate/forward_fit.hpp"
#include "decode/calibrate/kernel_estimate.hpp"
#include "decode/calibrate/kernel_fit.hpp"
#include "decode/calibrate/lattice_fft.hpp"
#include "decode/calibrate/saturation.hpp"
#include "decode/calibrate/spots.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask::calibrate {

struct CalibrationOptions {
    double max_rotation_deg = 5.0;  // rotations searched: +- this (--max-rotation)
    double pitch_range = 0.05;      // pitches searched: design pixels per cell +- this fraction
    double threshold_sigmas = 6.0;  // spot detection threshold (decode/calibrate/spots)
    double saturation_level = std::numeric_limits<double>::infinity();  // raw counts
    // With no saturation_level (infinite): a flat top at the capture's largest value
    // (decode/calibrate/saturation) is taken as its ceiling, and its spots as saturated.
    bool detect_saturation = true;
    // More than this fraction of spots with a saturated pixel: centroids and gains are unusable.
    double max_saturated_fraction = 0.5;
    // Fewer spots than this fraction of the design's in-frame pinholes: the capture is not of
    // this mask (or is badly out of focus).
    double min_spot_fraction = 0.5;
    // The one-period cyclic PSF is made when the lattice drifts by at most this over one
    // period (pixels): beyond, a cyclic PSF on a whole-pixel torus misplaces spots.
    double period_tolerance_px = 0.5;
    // Sensor pixels per capture pixel along each axis (2 for a Bayer RAW read as 2 x 2 blocks):
    // the design's pitch in capture pixels is pixels_per_cell / pixel_binning. The mask's camera
    // must already carry the capture's pixel pitch (the kernel models use it).
    int pixel_binning = 1;
    // Progress for the faces (may be empty): a phase's name when it starts ("finding the
    // lattice (FFT)", "fitting the forward model", "building the calibrated PSF") with iteration
    // 0, and during the fit its Levenberg-Marquardt iterations so far (every round counted) and
    // a round's cap.
    std::function<void(const std::string& phase, int iteration, int cap)> progress;
};

// Throws InvalidInput naming the field, the value and the rule.
void validate(const CalibrationOptions& options);

struct CalibrationSummary {
    // The fit of the forward model (decode/calibrate/forward_fit): rotation counter-clockwise on
    // screen with rows running down (scipy.ndimage.rotate's sense), pitches along the mask's axes.
    double rotation_deg = 0.0, rotation_sigma_deg = 0.0;
    double pitch_x_px = 0.0, pitch_y_px = 0.0, pitch_x_sigma_px = 0.0, pitch_y_sigma_px = 0.0;
    double position_x_px = 0.0, position_y_px = 0.0;  // spot centre of pattern cell (0, 0) in
    double position_sigma_px = 0.0;                   // the first full tile (row-major order)
    Cell first_tile;                                  // that tile (row, col)
    double design_pitch_px = 0.0;                     // the design's pitch at u (capture pixels)
    ForwardFit fit;
    // Spots above the threshold (the refusals of unusable captures) and the lattice's start
    // from the capture's Fourier transform (decode/calibrate/lattice_fft).
    std::vector<Spot> spots;
    FftStart fft_start;
    std::vector<Cell> missing;  // mask cells (R, C) over the tiled mask, decided by the fit
    // Blobs of the normalised residual above the threshold carrying at least a quarter of the
    // median pinhole flux: light the design does not explain (a pinhole not in the design, a
    // scratch). (x, y, flux).
    std::vector<std::array<double, 3>> extra_spots;
    std::vector<int> saturated_spots;  // indices into spots
    SaturatedPlateau plateau;          // the flat top found when no saturation level was given
    // What the faces print as warnings (fields as references): a plateau that did not refuse
    // the capture.
    std::vector<std::string> warnings;
    double dark_level = std::numeric_limits<double>::quiet_NaN();  // counts, NaN: not measured
    std::string dark_source;  // "dark frame", "fitted background", "not measured"
    // The light's band as the fit treats it: the kernel is one wavelength's, the band's centre;
    // a camera with a band (bandwidth_m > 0) is fitted there and this says so and what it does.
    std::string band;
    double background = 0.0, background_sigma = 0.0;  // leak per pixel inside the footprint
    // -log10(leak per cell / median pinhole flux) with its standard error; when the leak is not
    // significant (below 2 sigma) the value is a lower bound (from leak + 2 sigma) and
    // optical_density_is_bound is set. Never negative. NaN when the leak is not measured (the
    // mask's footprint fills the frame and no dark frame fixes the background).
    double optical_density = std::numeric_limits<double>::infinity();
    double optical_density_sigma = 0.0;
    bool optical_density_is_bound = false;
    double noise_sigma = 0.0;  // sqrt of the noise model's variance at the background level
    KernelEstimate kernel;     // the fitted kernel on a window
    std::vector<ModelResidual> kernel_fit;
    std::string best_model;
    CalibratedPsfs psfs;
    Plane residual_map;  // capture (after the dark frame) - fitted model
};

// Throws InvalidInput (exit 2 in the CLI) for: an empty/non-finite capture or dark frame of
// another size; a capture whose scale is out of range (decode/calibrate/saturation); a capture
// smaller than one period; no spots; far fewer spots than the design; saturation over most spots
// (at the given level, or at a flat top found when none is given); a lattice outside the
// searched rotation/pitch range.
CalibrationSummary calibrate_point_source(const Plane& capture, const std::optional<Plane>& dark,
                                          const Mask& mask, const CalibrationOptions& options = {});

}  // namespace pinmask::calibrate
