// The ONE set of mask metrics and the ONE scene prior used by `pinmask score`, `compare`,
// `search` and the masks/ table: the same mask under the same settings gives the
// same numbers in every command.
//
// Metrics of a mask (n x n pattern, K pinholes, ppc pixels per cell, period m = n ppc):
//   sidelobes   torus autocorrelation (optimize/metrics/autocorrelation)
//   spectrum    min |P^|, flatness, OTF condition over the kernel passband, spectral zeros
//               (optimize/metrics/spectrum_metrics)
//   analytic    closed-form expected Wiener PSNR for each noise level
//   (optimize/metrics/analytic_error):
//               the fixed-NSR filter (given or tuned) and the per-frequency optimal bound
//   robust      with `robust` errors: the analytic figure's expectation under fabrication
//               errors, decoded with the nominal PSF (optimize/metrics/robust_wiener)
//   wiener, tv  simulated one-period captures of the scenes, decoded
//   (optimize/metrics/simulated_metrics) depth       the Cramer-Rao bound on the object distance of
//   a point source on the axis over
//               a range of distances, per photon-model level (optimize/metrics/depth_fisher): the
//               worst relative bound and the worst axial resolution (FWHM) over the range
// The analytic prior is make_scene_prior(options.prior, m): by default 16 natural 1/f textures
// of seeds 1000 .. 1015 (apart from the scored "natural" scene, seed 0).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {

// ---- The scene prior ----
enum class PriorKind { kNatural, kText, kStars, kFiles };

// One name table: natural, text, stars, files.
const std::vector<std::pair<PriorKind, std::string>>& prior_kind_names();
std::string prior_kind_name(PriorKind kind);

inline constexpr int kDefaultPriorScenes = 16;
inline constexpr std::uint64_t kPriorFirstSeed = 1000;
inline constexpr int kMaxPriorScenes = kMaxPriorSceneCount;  // optimize/simulate/scene_prior

struct PriorSpec {
    PriorKind kind = PriorKind::kNatural;
    int count = kDefaultPriorScenes;  // sample scenes (natural, text, stars), 1 .. 4096
    std::uint64_t first_seed = kPriorFirstSeed;
    std::vector<std::filesystem::path> files;  // kFiles: the images (resampled to the period)

    // InvalidInput naming `prior` / `prior.count`, the value and the rule.
    void validate() const;
    std::string description() const;  // "natural (16 1/f textures, seeds 1000..1015)"
};

// "natural", "text", "stars", or image files separated by commas. InvalidInput naming `prior`.
PriorSpec parse_prior_spec(const std::string& text, int count = kDefaultPriorScenes);

// The prior at an m x m period.
ScenePrior make_scene_prior(const PriorSpec& spec, int m);

// Frequencies the prior makes irrelevant: k != 0 with S(k) < fraction * max_{k != 0} S(k).
// Their terms in the analytic error are below that fraction of the largest one, whatever the
// mask does there (the error still sums them: nothing is skipped in the evaluation).
inline constexpr double kIrrelevantPriorFraction = 1e-6;
struct PriorRelevance {
    long long irrelevant = 0;              // frequencies below the fraction
    long long total = 0;                   // frequencies k != 0
    double highest_relevant_radius = 0.0;  // largest |k| (cycles per period) above the fraction
};
PriorRelevance prior_relevance(const ScenePrior& prior, double fraction = kIrrelevantPriorFraction);

// ---- Noise levels ----
// A noise model with the suffix of its keys: Gaussian at S dB -> "snrS", photon level P -> "phP".
struct NoiseLevel {
    NoiseModel model;
    std::string key;
};
NoiseLevel noise_level(const NoiseModel& model);

// ---- Metrics ----
struct MaskMetricsOptions {
    bool sidelobes = true, spectrum = true, analytic = true, wiener = true, tv = false;
    bool depth = false;  // needs every noise level to be the photon model
    DepthRange depth_range;
    std::vector<NoiseLevel> noise{noise_level(NoiseModel{})};  // Gaussian 30 dB
    PriorSpec prior;
    std::vector<SceneSpec> scenes;       // simulated scenes (wiener, tv)
    SimulatedMetricsOptions simulation;  // its wiener_nsr is also the analytic fixed filter
    double spectral_zero_threshold = kSpectralZeroThreshold;
    // Fabrication errors (`robust`): with any, the analytic figures gain the expected PSNR under
    // them, decoded with the nominal PSF (optimize/metrics/robust_wiener.hpp).
    FabricationErrors robust;

    // InvalidInput naming the field, value and rule.
    void validate() const;
};

struct AnalyticFigures {
    double psnr_db = 0.0;       // the fixed-NSR filter (given, or tuned per mask and level)
    double nsr = 0.0;           // its NSR
    double mmse_psnr_db = 0.0;  // the per-frequency optimal (MMSE) Wiener filter
};

// The analytic fixed-NSR figure under fabrication errors (same filter and NSR as
// AnalyticFigures::psnr_db): expected PSNR and the loss against the nominal figure.
struct RobustFigures {
    double psnr_db = 0.0;
    double loss_db = 0.0;
};

struct LevelMetrics {
    NoiseLevel level;
    std::optional<AnalyticFigures> analytic;
    std::optional<RobustFigures> robust;  // analytic with options.robust errors
    std::optional<SimulatedQuality> wiener, tv;
    std::optional<DepthFigures> depth;
};

struct MaskMetrics {
    int n = 0, holes = 0, pixels_per_cell = 0, period_px = 0;
    std::string kernel_description;
    std::optional<SidelobeMetrics> sidelobes;
    std::optional<PatternSpectrumMetrics> spectrum;
    std::optional<OtfCondition> otf;
    std::optional<SpectralZero> spectral_zero;
    std::vector<LevelMetrics> levels;  // one per options.noise entry
};

// The per-period data shared by masks of one period: rendered scenes and the prior.
class MetricsContext {
  public:
    explicit MetricsContext(MaskMetricsOptions options);
    const MaskMetricsOptions& options() const { return options_; }
    const std::vector<NamedScene>& scenes(int m);
    const ScenePrior& prior(int m);

  private:
    MaskMetricsOptions options_;
    std::map<int, std::vector<NamedScene>> scenes_;
    std::map<int, std::shared_ptr<ScenePrior>> priors_;
};

// The metrics the options ask for.
MaskMetrics compute_mask_metrics(const Mask& mask, MetricsContext& context);

}  // namespace pinmask
