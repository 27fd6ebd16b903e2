// The settings a decode reads from the capture and the PSF when the user leaves them to it
// (`auto`, the faces' default): the convolution model, the crop, the background, the method and
// non-negativity. Each rule is stated here with what it was measured on (docs/decoding.md,
// "Defaults read from the capture"); the pipeline (decode/capture/capture_pipeline.hpp) applies
// them and records each choice with its reason.
#pragma once

#include <string>

#include "core/image/image.hpp"

namespace pinmask {

// One setting chosen from the data: its name ("model", "crop", "background", "nonnegative"), the
// value chosen (the faces' spelling: "linear", "none", ...) and why, one line.
struct ChosenSetting {
    std::string name, value, reason;
};

// Model: a PSF at least as large as the capture along both axes is a lensless camera's response
// over its sensor (a DiffuserCam PSF, a measured lensless array), decoded with the linear model,
// unless the PSF is known to be one period of a mask's cyclic tiling (synthesised from a mask,
// or a PSF file whose pinmask sidecar says "cyclic"; a "full-frame" one is a response over the
// sensor). A PSF smaller than the capture along an axis is one
// period of a tiling: cyclic (the period check measures the repeat).
bool psf_covers_capture(int capture_rows, int capture_cols, int psf_rows, int psf_cols);

// The fraction of a measured PSF's pixels taken as its dark floor.
inline constexpr double kPsfFloorQuantile = 0.05;

// Background auto reads a PSF that covers the capture and holds whole numbers (a measured image
// in counts; a computed or rescaled PSF has no camera floor to read).
// A measured PSF's dark floor: its kPsfFloorQuantile quantile (a point source lights less than
// 95 % of the sensor; the DiffuserCam tutorial's PSF: 32 counts against its corner patch's 34),
// or 0 when that is not positive (a synthesised PSF).
double psf_floor(const Plane& psf);

// True when every value of every channel is a whole number (sensor counts): the PSF's floor is
// then subtracted from the capture too only when both are counts (the same camera's units).
bool whole_numbers(const Image& image);
// A quantile at least this fraction of the PSF's peak is light (a flat or broad PSF), not a
// floor: nothing is subtracted.
inline constexpr double kPsfFloorMaxOfPeak = 0.1;
bool whole_numbers(const Plane& plane);

// Non-negativity (tv, tvqc): the capture is an intensity when its 0.1 % quantile is at least
// -3 sigma (sigma the capture's noise, decode/solvers/noise_estimate.hpp, largest over the
// channels): a sensor's counts after the dark level, noise included. `low` and `sigma` are set.
bool capture_is_intensity(const Image& capture, double& low, double& sigma);

// Frame filling: the mean magnitude of a capture's border band (kBorderBandDivisor-th of the
// smaller side wide, at least 1 px) over the mean magnitude of the whole capture; 0 when the
// band would cover the capture or the capture is all zero. A scene lit to the sensor's edges
// reads about 1; an object in the middle of a dark frame, about 0.
inline constexpr int kBorderBandDivisor = 16;
double border_fill(const Plane& capture);
// A capture fills the frame when its border band averages at least this fraction of its mean
// magnitude (in any channel): the linear model's closed forms (wiener, tikhonov) then read the
// light that came from beyond the sensor as zero and ring from the edges.
inline constexpr double kFrameFillingBorderFill = 0.5;
// The largest border_fill over the channels.
double border_fill(const Image& capture);

// Method: tv on the linear model (it solves the model with its crop exactly: the light from
// beyond the sensor is unknown, not zero), wiener on the cyclic model (its exact least-error
// filter). Measured against wiener on the linear model (docs/decoding.md): the refocus of a
// frame-filling scene (scripts/refocus_phone.py), the real hand and USAF captures, whose borders
// are dark (scripts/real_defaults_table.py --auto), and the rendered lensless rows of the
// automatic-weight table, where tv leads by 8-16 dB.
bool auto_method_is_tv(bool linear_model);

}  // namespace pinmask
