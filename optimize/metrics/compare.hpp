// The figures `pinmask compare` puts side by side, gathered from optimize/simulate/,
// optimize/metrics/ and decode/: per mask a metrics row (sidelobes, spectrum, OTF condition,
// analytic and simulated error) and the pictures of its report page (pattern, PSF, log |OTF|,
// autocorrelation, scene, capture, Wiener and TV reconstructions), plus the baselines (random
// median, paper-like geometry, MURA).
//
// Notation: n grid, K pinholes, ppc pixels per cell, m = n ppc the period in pixels; P^ the
// n x n pattern DFT, A^ the m x m OTF of the sum-1 PSF (design/psf/psf.hpp). Simulated figures use
// the cyclic model on one period (optimize/metrics/simulated_metrics); every metric comes from
// optimize/metrics/mask_metrics, the set score and search use, so the numbers agree across
// commands. The first noise level is the one shown on the pages and used to rank the random
// baseline.
//
// The lead figure: a comparison leads with the figure the first mask's search optimised
// (provenance.objective_figure: analytic_mmse_psnr_db or analytic_wiener_psnr_db, the names of
// io/metrics_json.hpp), else the one `search` optimises by default under the first noise level
// (parse_search_filter "auto"). The random baseline is ranked by it, every mask's difference to
// the first is given on it (exact: a closed form) and on the simulated figures (paired over the
// scenes, with a standard error: optimize/metrics/paired_difference), and the first mask's gain
// over the random median on it carries the median's standard error.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/figure_names.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/paired_difference.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {

inline constexpr int kMaxBaselineCount = 10000;

struct CompareSettings {
    // Noise levels (first: shown and ranks the baseline), prior, scenes ([0] is shown), weights;
    // sidelobes, spectrum, analytic, wiener and tv are all computed.
    MaskMetricsOptions metrics;
    std::uint64_t seed = 1;  // baseline draws (the noise seed is metrics.simulation.seed)
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
    // First level. Closed form over the prior: the Wiener filter of one NSR (the setting, given
    // or tuned), and the per-frequency optimal (MMSE) filter.
    double analytic_wiener_psnr_db = 0.0, analytic_wiener_nsr = 0.0;
    double analytic_mmse_psnr_db = 0.0;
    // analytic Wiener expected under the --robust fabrication errors, first level; NaN without
    double analytic_robust_wiener_psnr_db = std::numeric_limits<double>::quiet_NaN();
    // Simulated on the scenes, first level, mean over scenes.
    double sim_wiener_psnr_db = 0.0, sim_wiener_ssim = 0.0, sim_wiener_nsr = 0.0;
    double sim_tv_psnr_db = 0.0, sim_tv_ssim = 0.0, sim_tv_lambda = 0.0;
    MaskMetrics metrics;  // every level's figures, as score computes them
    // The difference to the first mask (row b minus the first row), by figure name: the lead
    // figure, sim_wiener_psnr_db, sim_tv_psnr_db. Empty for the first mask.
    std::vector<std::pair<std::string, PairedDifference>> to_first;
};

// A CompareRow's first-level figure by its name (analytic_mmse_psnr_db, analytic_wiener_psnr_db,
// sim_wiener_psnr_db, sim_tv_psnr_db); NaN for another name.
double row_figure(const CompareRow& row, const std::string& name);

// The figure a comparison leads with (the rule at the top) and why, in words.
struct LeadFigure {
    std::string name;    // analytic_mmse_psnr_db or analytic_wiener_psnr_db
    std::string reason;  // "the figure the first mask's search optimised", ...
};
LeadFigure compare_lead_figure(const Mask& first, const NoiseModel& noise);

// The pictures of one mask's report page, and the figures of the shown reconstructions.
struct ComparePictures {
    Plane pattern;          // n x n, 1 = clear pinhole
    Plane psf;              // m x m, sum 1
    Plane log_otf;          // m x m, log10 |A^| / |A^(0)|, zero frequency at (m/2, m/2)
    Plane autocorrelation;  // n x n, R(d), zero shift at (n/2, n/2)
    std::string scene_name;
    Plane scene, capture, wiener, tv;  // m x m (channel mean for colour scenes)
    double capture_sigma = 0.0;        // mean noise standard deviation of the shown capture
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

// Rule: a comparison report describes one camera (page 1 prints it, the baselines are built for
// it), so every mask must be designed for the first mask's camera; grid sizes may differ. Throws
// InvalidInput naming `path`'s optics field and both values.
void require_same_camera(const Mask& first, const Mask& m, const std::string& path);

// Every metric and picture of one mask. `context` holds settings.metrics (the caller builds it
// once: scenes and prior are shared by masks of one period).
CompareResult compare_mask(const CompareEntry& entry, const CompareSettings& settings,
                           MetricsContext& context);

// The random baseline: `count` random valid patterns with the template's n, K, spacing and tiles
// (draw i from std::mt19937_64(seed + i)), camera and PSF settings of the template, ranked by
// the `figure` (analytic_mmse_psnr_db, or analytic_wiener_psnr_db at the settings' NSR) at the
// first noise level; the entry is the median draw (index (count - 1) / 2 of the ascending
// ranking). InvalidInput when count is outside 1 .. kMaxBaselineCount, random placement
// cannot place K pinholes, or the figure is another. `progress(done, count)` is called after
// each draw.
struct RandomMedian {
    CompareEntry entry;
    std::string figure;  // what ranks the draws
    std::uint64_t median_seed = 0;
    double min_psnr_db = 0.0, median_psnr_db = 0.0, max_psnr_db = 0.0;
    // The median's standard error as an estimate of the population's (paired_difference.hpp).
    double median_standard_error_db = 0.0;
    int count = 0;
};
RandomMedian random_median_baseline(const Mask& tmpl, int count, const CompareSettings& settings,
                                    MetricsContext& context, const std::string& figure,
                                    const std::function<void(int, int)>& progress = {});

// The paper's geometry (design/pattern/families paper_pattern, seeded with settings.seed) with the
// template's camera and PSF settings.
CompareEntry paper_like_baseline(const Mask& tmpl, std::uint64_t seed);

// The largest prime p = 4m + 1 <= n, or 0 when there is none (n < 5).
int mura_order_at_most(int n);

// The MURA of order p = mura_order_at_most(tmpl n) with the template's camera, PSF settings,
// tiles and min spacing, recorded as breaking the spacing rule. Requires p >= 5.
CompareEntry mura_baseline(const Mask& tmpl, int p);

// ---- The whole comparison ----
struct CompareRunOptions {
    CompareSettings settings;
    bool baselines = false;    // add random-median, paper-like and MURA rows
    int baseline_count = 100;  // random draws, 1 .. kMaxBaselineCount
    void validate() const;
};

// The baselines' sources and lines and the skip reasons name settings by field reference
// (core/errors/field_names.hpp: "`seed`"); a face spells them in its own words before showing them.
struct CompareOutcome {
    std::vector<CompareResult> results;        // given masks first, then the baselines
    std::vector<std::string> baseline_lines;   // what each baseline is, or why it is missing
    std::optional<RandomMedian> random;        // without the entry's mask
    std::string random_skipped, mura_skipped;  // why a baseline is missing ("" when present)
    int mura_order = 0;
    LeadFigure lead;  // the figure the table leads with and the random baseline is ranked by
    // The first mask's gain over the random median on the lead figure: its standard error is
    // the median's (the first mask's figure is exact). Absent without the random baseline.
    std::optional<PairedDifference> random_gain;
    // When the first mask's file records the lead figure (a search's score) and compare computes
    // another value (other noise, prior or NSR): the line that says so; "" otherwise.
    std::string lead_mismatch;
};

// Progress: (phase, done, total), phase "random baseline" or "mask" (done masks before this
// one starts); total 0: a set-up phase starting, named by phase.
using CompareProgress = std::function<void(const std::string&, int, int)>;

// Every mask of `entries` (at least one; the first sets the camera of the baselines) and the
// baselines, each with every metric and picture.
CompareOutcome run_compare(std::vector<CompareEntry> entries, const CompareRunOptions& options,
                           const CompareProgress& progress = {});

}  // namespace pinmask
