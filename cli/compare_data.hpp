// The figures `pinmask compare` puts side by side, gathered from optimize/ and decode/: per
// mask a metrics row (sidelobes, spectrum, OTF condition, analytic and simulated error) and the
// pictures of its report page (pattern, PSF, log |OTF|, autocorrelation, scene, capture, Wiener
// and TV reconstructions), plus the baselines (random median, paper-like geometry, MURA).
//
// Notation: n grid, K pinholes, ppc pixels per cell, m = n ppc the period in pixels; P^ the
// n x n pattern DFT, A^ the m x m OTF of the sum-1 PSF (design/psf.hpp). Simulated figures use
// the cyclic model on one period with Gaussian noise at the SNR (optimize/simulated_metrics).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cli/analytic_setup.hpp"
#include "core/image.hpp"
#include "design/mask.hpp"
#include "optimize/analytic_error.hpp"
#include "optimize/scenes.hpp"
#include "optimize/simulated_metrics.hpp"

namespace pinmask::cli {

struct CompareSettings {
    double snr_db = 30.0;           // capture SNR, dB (finite)
    std::vector<SceneSpec> scenes;  // simulated scenes; [0] is shown
    WienerFilterSpec analytic_filter{WienerFilterKind::kOptimal, 0.0};  // analytic Wiener PSNR
    int prior_scenes = kDefaultPriorScenes;  // analytic prior textures, >= 1
    WeightChoice wiener_nsr{true, 0.01};     // simulated Wiener NSR
    WeightChoice tv_lambda{false, 1e-3};     // simulated TV-L2 lambda
    int tv_iterations = 200;                 // TV-L2 ADMM iterations, >= 1
    std::uint64_t seed = 1;                  // noise generators and baseline draws
};

// One mask to compare: a file given on the command line or a baseline.
struct CompareEntry {
    std::string name;    // table label
    std::string kind;    // "input", "random-median", "paper-like", "mura"
    std::string source;  // the file path, or how the baseline was made
    Mask mask;
};

// The metrics of one mask (units in the names; NaN/inf where a figure has none).
struct CompareRow {
    std::string name, kind, source, geometry_hash;
    int n = 0, holes = 0, pixels_per_cell = 0, period_px = 0;
    bool spacing_ok = true;  // no pair closer than min_spacing_cells on the torus
    long long spacing_violations = 0;
    double min_spacing_cells = 0.0;
    int max_sidelobe = 0;
    double peak_to_sidelobe_ratio = 0.0;  // +inf without sidelobes
    double min_abs_pattern_spectrum = 0.0;
    double spectral_flatness = 0.0;
    double otf_condition_number = 0.0;  // +inf with a spectral zero in the passband
    double analytic_wiener_psnr_db = 0.0;
    double wiener_psnr_db = 0.0, wiener_ssim = 0.0, wiener_nsr = 0.0;  // mean over scenes
    double tv_psnr_db = 0.0, tv_ssim = 0.0, tv_lambda = 0.0;
};

// The pictures of one mask's report page, and the figures of the shown reconstructions.
struct ComparePictures {
    Plane pattern;          // n x n, 1 = clear pinhole
    Plane psf;              // m x m, sum 1
    Plane log_otf;          // m x m, log10 |A^| / |A^(0)|, zero frequency at (m/2, m/2)
    Plane autocorrelation;  // n x n, R(d), zero shift at (n/2, n/2)
    std::string scene_name;
    Plane scene, capture, wiener, tv;  // m x m (channel mean for colour scenes)
    double capture_sigma = 0.0;        // noise standard deviation of the shown capture
    double wiener_psnr_db = 0.0, wiener_ssim = 0.0, tv_psnr_db = 0.0, tv_ssim = 0.0;
    int tv_iterations = 0;
    std::string kernel;  // kernel model and why
};

struct CompareResult {
    CompareRow row;
    ComparePictures pictures;
};

// Throws InvalidInput naming the field when the settings are out of range.
void validate(const CompareSettings& settings);

// Scenes rendered at each period size, shared by masks of the same period.
class SceneCache {
  public:
    const std::vector<NamedScene>& at(int m, const std::vector<SceneSpec>& specs);

  private:
    std::map<int, std::vector<NamedScene>> cache_;
};

// Every metric and picture of one mask.
CompareResult compare_mask(const CompareEntry& entry, const CompareSettings& settings,
                           SceneCache& scenes);

// The random baseline: `count` random valid patterns with the template's n, K, spacing and tiles
// (draw i from std::mt19937_64(seed + i)), camera and PSF settings of the template, ranked by
// simulated Wiener PSNR; the entry is the median draw (index (count - 1) / 2 of the ascending
// ranking). InvalidInput when count < 1 or random placement cannot place K pinholes.
struct RandomMedian {
    CompareEntry entry;
    std::uint64_t median_seed = 0;
    double min_psnr_db = 0.0, median_psnr_db = 0.0, max_psnr_db = 0.0;
    int count = 0;
};
RandomMedian random_median_baseline(const Mask& tmpl, int count, const CompareSettings& settings,
                                    SceneCache& scenes);

// The paper's geometry (design/families paper_pattern, seeded with settings.seed) with the
// template's camera and PSF settings.
CompareEntry paper_like_baseline(const Mask& tmpl, std::uint64_t seed);

// The largest prime p = 4m + 1 <= n, or 0 when there is none (n < 5).
int mura_order_at_most(int n);

// The MURA of order p = mura_order_at_most(tmpl n) with the template's camera, PSF settings,
// tiles and min spacing, recorded as breaking the spacing rule. Requires p >= 5.
CompareEntry mura_baseline(const Mask& tmpl, int p);

}  // namespace pinmask::cli
