// Simulated reconstruction quality over one period, for `pinmask score`: the cyclic forward
// model (docs/design.md section 2) on an m x m period,
//     capture = scene (*) psf + Gaussian noise at an SNR (optimize/simulate/noise_model.hpp: sigma
//     from
//               this capture's own mean square),
// with the PSF centred as the decoder expects (deconvwnr parity, decode/solvers/psf2otf.hpp),
// decoded by Wiener (decode/solvers/wiener.hpp) or TV-L2 (decode_plane, method kTv, cyclic model)
// and compared with the scene. No full-sensor simulation: on the cyclic model one period carries
// every metric. Channels are simulated and decoded independently (one for grey scenes, three for
// RGB).
//
// Aggregation: for each scene, PSNR = 10 log10(1 / MSE) with the MSE averaged over channels and
// noise seeds; SSIM (optimize/simulate/image_quality.hpp) averaged likewise (NaN when the period is
// smaller than the 11 x 11 SSIM window). The mask's figure is the mean over scenes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

struct NamedScene {
    std::string name;
    Image image;  // m x m, values in [0, 1]
};

// A regularisation weight (Wiener NSR, TV lambda): fixed, or tuned to minimise the mean MSE over
// all scenes, channels and seeds by golden section on log10 (optimize/metrics/nsr_tuning.hpp).
struct WeightChoice {
    bool tuned = false;
    double value = 0.01;  // used when not tuned; > 0
};

struct SimulatedMetricsOptions {
    // The mean settles long before 1000 realisations; more is a run that never ends.
    static constexpr int kMaxNoiseSeeds = 1000;
    int noise_seeds = 1;     // noise realisations per scene, channel and SNR, 1..1000
    std::uint64_t seed = 0;  // base of every noise generator (std::seed_seq with the indices)
    WeightChoice wiener_nsr{false, 0.01};
    WeightChoice tv_lambda{false, 1e-3};
    int tv_iterations = 200;  // TV-L2 ADMM iterations, >= 1
    double tv_tolerance = 1e-4;

    // Throws InvalidInput naming the field, value and rule.
    void validate() const;
};

enum class SimulatedDecoder { kWiener, kTv };

struct SceneQuality {
    std::string scene;
    double psnr_db = 0.0;
    double ssim = 0.0;  // NaN when the period is below the SSIM window
};

struct SimulatedQuality {
    double weight = 0.0;        // the NSR or lambda used (tuned or given)
    double mean_psnr_db = 0.0;  // mean over scenes
    double mean_ssim = 0.0;     // mean over scenes (NaN as above)
    std::vector<SceneQuality> scenes;
    long long decodes = 0;  // decoder runs, tuning included (a tuned Wiener NSR needs none)
};

// Simulates every scene at `snr_db` and decodes with `decoder`. psf: m x m, sum > 0; every scene
// m x m (InvalidInput otherwise). Deterministic for the same inputs.
SimulatedQuality simulated_quality(const Plane& psf, const std::vector<NamedScene>& scenes,
                                   double snr_db, SimulatedDecoder decoder,
                                   const SimulatedMetricsOptions& options);

// The same under any noise model (optimize/simulate/noise_model): open_cells (K) and total_cells
// (n^2) set the photon model's signal and film leak (unused by the Gaussian model).
SimulatedQuality simulated_quality(const Plane& psf, const std::vector<NamedScene>& scenes,
                                   const NoiseModel& noise, int open_cells, int total_cells,
                                   SimulatedDecoder decoder,
                                   const SimulatedMetricsOptions& options);

}  // namespace pinmask
