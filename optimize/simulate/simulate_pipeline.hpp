// The whole `pinmask simulate` as one library call: mask -> PSF of one period (its
// kernel), scene rendered at the period, the capture under the noise model (one period, tiled
// over the sensor, or the exact geometry of design/psf/psf_exact over a sensor window), and the
// dark frame. Returns the images and a Summary with the --explain lines; never prints.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/units/units.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"

namespace pinmask {

struct SimulatePipelineOptions {
    SceneSpec scene = scene_from_name("letter-R");
    // noise, seed, full_sensor, dark_frame, precision. The sensor size is the mask camera's (or
    // `sensor`); exact_psf is set by the pipeline.
    SimulationOptions sim;
    std::optional<Size2> sensor;  // full_sensor: WIDTHxHEIGHT instead of the mask's camera
    bool exact_geometry = false;  // every pinhole at its true position (design/psf/psf_exact)
    std::optional<double> object_distance_m;  // exact: u (may be inf), default the mask's
    std::optional<Size2> window;  // exact: the ROWSxCOLS window as typed (cols = ROWS, rows = COLS)
    std::vector<std::string> noise_notes;  // explain lines about the noise model, after its line
    // Photon model: the sensor stages asked for, which its explain line lists (a stage at its
    // neutral value, e.g. read noise 0, is still listed when asked for).
    struct PhotonStages {
        bool leak = false, dark_current = false, read_noise = false, saturation = false,
             adc = false;
    } photon_stages;

    // InvalidInput naming the field, value and rule: `sensor` only with full_sensor; exact
    // geometry excludes full_sensor and `sensor`; `object_distance_m` and `window` only with
    // exact geometry.
    void validate() const;
};

struct SimulatePipelineSummary {
    int period_px = 0;  // m: the PSF period in pixels
    int holes = 0;      // K
    Kernel kernel;      // the pinhole kernel the PSF was synthesised with
    std::string scene_name;
    int scene_channels = 0;
    double object_distance_m = 0.0;    // exact geometry: the u used
    bool single_precision = false;     // the convolution ran in float32 (SimulationOptions)
    std::vector<std::string> explain;  // what was run and skipped, and why (for --explain)
};

struct SimulatePipelineResult {
    SimulatedCapture capture;  // capture, dark frame, background, tiling origin
    SimulatePipelineSummary summary;
};

SimulatePipelineResult run_simulate_pipeline(const Mask& mask,
                                             const SimulatePipelineOptions& options);

}  // namespace pinmask
