// Forward simulation of a capture: scene (*) PSF over one period (the cyclic model,
// docs/design.md section 2), optionally tiled over the whole sensor, with a sensor noise model
// (optimize/simulate/noise_model.hpp), a film-leakage background and a matching dark frame.
//
// Units: captures are in the normalised units of noise_model.hpp: a uniform scene of value v
// gives v everywhere when noiseless. For the photon model that is electrons / (ppp K) (ppp =
// photons_per_pinhole, K = open cells), so the raw electron count is capture * ppp K.
//
// Forward model (one period, m_r x m_c = the PSF's size): c = a (*) x, circular convolution with
// the PSF centred as the decoder expects (decode/solvers/psf2otf.hpp: the PSF's central element
// (floor(m_r / 2), floor(m_c / 2)) is the zero shift), so decode_plane(c, a) returns x with no
// shift. Full sensor: the sensor behind a cyclic mask sees the period repeated; the frame is the
// periodic extension of the one-period capture, which is exact for the cyclic model:
//     frame(r, c) = period((r - r0) mod m_r, (c - c0) mod m_c),
// with the origin (r0, c0) = ((R - m_r) / 2, (C - m_c) / 2) (rounded down, R x C the sensor), so
// the centred period crop of decode/capture/capture.hpp (CropMode::kCenter) returns the period
// exactly. Noise is drawn per pixel of the frame (one independent draw per sensor pixel, not
// tiled).
//
// Background and dark frame (photon model only): add_noise returns the capture with the expected
// offset (film leak + dark current, noise_model.hpp) removed; the simulated raw capture puts it
// back, as a real sensor records it: raw = add_noise(c) + offset_e / (ppp K). The dark frame is
// the capture of the same exposure through all-opaque film: no pinhole signal, the same leak and
// dark current (a Poisson count of mean offset_e: the sum of the two Poisson terms), read noise,
// saturation and ADC, in the same units. It is drawn from its own seed stream, so asking for it
// does not change the capture. Subtracting it (pinmask decode --dark) removes the background.
//
// Precision: the convolutions (cyclic_capture, linear_capture) run in double, or in float32 (FFTW
// float) on the scene divided by max|x| and the PSF divided by sum|a| (so every float value is
// at most 1 and the FFT sums at most N, whatever the inputs' scale: no overflow), scaled back in
// double. Noise, tiling, background and the dark frame are always double. kAuto picks float32
// for a convolution grid of at least kSinglePrecisionMinPixels (256 x 256). The float capture
// differs from the double one by float rounding:
// tests/optimize/simulate/test_simulate_precision.cpp states the bound.
//
// Seeds: channel ch of the capture draws from std::mt19937_64(seed_seq{seed low 32 bits, seed
// high 32 bits, 0, ch}); the dark frame uses stream 1 in place of 0.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

struct SimulationOptions {
    NoiseModel noise;          // kind kNone: noiseless
    bool full_sensor = false;  // tile the period over sensor_rows x sensor_cols
    int sensor_rows = 480;     // >= 1, used when full_sensor
    int sensor_cols = 720;
    bool dark_frame = false;  // also draw the dark frame (photon model only)
    std::uint64_t seed = 1;
    // Exact geometry (design/psf/psf_exact.hpp): when set, the frame is linear_capture(scene,
    // *this) at this PSF's size (the sensor window) instead of the tiled cyclic capture;
    // full_sensor and the sensor size are then ignored. Not owned: must outlive the
    // simulate_capture call.
    const Plane* exact_psf = nullptr;
    // The convolution's precision (see above); kDouble keeps the library's historical bytes.
    Precision precision = Precision::kDouble;

    // Throws InvalidInput naming the field: the noise model (noise_model.hpp validate), sensor
    // size >= 1 when full_sensor, dark_frame only with the photon model (the Gaussian SNR model
    // has no dark signal to record).
    void validate() const;
};

// Where the period sits in a tiled frame: frame(r, c) = period((r - row) mod m_r, (c - col) mod
// m_c).
struct TileOrigin {
    int row = 0;
    int col = 0;
};

struct SimulatedCapture {
    Image capture;  // the period (m_r x m_c) or the sensor frame; background included
    Image dark;     // same size and channels, empty unless options.dark_frame
    Image clean;    // the noiseless capture without background, same size
    std::vector<double> background;      // per channel: the expected offset added (0 unless leak or
                                         // dark current), normalised units
    TileOrigin origin;                   // (0, 0) for a single period
    bool whole_period_on_sensor = true;  // full sensor: R >= m_r and C >= m_c
};

// The noiseless one-period capture a (*) x (decoder centring, see above), by FFT. scene and psf
// have the same size; psf finite with sum > 0; scene finite (InvalidInput otherwise). When both
// are non-negative the exact result is too, and FFT rounding below 0 is clipped to 0 (the photon
// model needs a non-negative capture).
// single_precision: the float32 convolution described at the top.
Plane cyclic_capture(const Plane& scene, const Plane& psf, bool single_precision = false);

// Exact geometry: the noiseless capture of an m_r x m_c scene through the sensor-window PSF w
// (R x C, the optical axis at its centre), linear convolution (no wrap-around):
//     c(r, c) = sum_{i, j} x(i, j) w(r - i + floor(m_r / 2), c - j + floor(m_c / 2)),
// i.e. scene pixel (i, j) is a point source (i - floor(m_r/2), j - floor(m_c/2)) pixels off the
// axis and shifts the whole PSF by that much; the result has the window's size. By zero-padded
// FFT; scene and PSF finite (InvalidInput otherwise), negative rounding clipped as above.
Plane linear_capture(const Plane& scene, const Plane& window_psf, bool single_precision = false);

// Whether a convolution on a rows x cols grid runs in float32 under `precision`.
bool simulate_in_single(Precision precision, long long rows, long long cols);

// The origin that puts a period at the centred crop of an R x C frame: ((R - m_r) / 2,
// (C - m_c) / 2), rounded towards minus infinity (negative when the frame is smaller).
TileOrigin centred_tile_origin(int frame_rows, int frame_cols, int period_rows, int period_cols);

// The periodic extension of `period` to rows x cols with the given origin (formula above).
// rows, cols >= 1; the frame size is checked against the memory bound (ResourceLimit).
Plane tile_period(const Plane& period, int rows, int cols, TileOrigin origin);

// The full simulation: every channel of `scene` (m_r x m_c, the PSF's size; values finite and
// >= 0) through the PSF, tiled when asked, noise and background, dark frame. open_cells and
// total_cells (K and n^2) enter the photon model only. Deterministic for the same inputs.
SimulatedCapture simulate_capture(const Image& scene, const Plane& psf, int open_cells,
                                  int total_cells, const SimulationOptions& options);

}  // namespace pinmask
