// The compare transaction: masks of one camera side by side, with baselines, and the pages of
// their report. One call (run_compare_request) for both faces: a request of typed settings in,
// the rows, the legends' words and the report pages out; io/compare_json renders the result and
// writes its files. The faces read the masks (io/mask_json) and parse the noise and prior.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "design/optics/camera.hpp"
#include "optimize/metrics/compare.hpp"

namespace pinmask {

struct CompareRequest {
    std::vector<CompareEntry> entries;  // the given masks, in order; one camera
    std::vector<NoiseLevel> noise;      // levels of the simulated and analytic figures
    std::string noise_text;             // the levels in words ("Gaussian noise at SNR 30 dB")
    // The Gaussian SNR (dB) both faces compare at when no noise level is given.
    static inline const std::vector<double> kDefaultSnrDb{30.0};
    PriorSpec prior;
    // search's default re-rank scenes: one mask shows one simulated figure in both.
    std::vector<std::string> scenes{"letter-R", "usaf", "siemens-star"};
    std::string wiener_nsr = "tuned";  // a number > 0 or "tuned"
    std::string tv_lambda = "1e-3";    // a number > 0 or "tuned"
    int tv_iterations = 200;
    std::uint64_t seed = 1;             // noise and baseline draws
    std::optional<std::string> robust;  // fabrication errors ("size=44um,jitter=2um")
    bool depth = false;                 // the depth columns (needs the photon model)
    double depth_from_m = 0.0;          // 0: the working distance / 2
    double depth_to_m = 0.0;            // 0: twice the working distance
    bool baselines = false;
    int baseline_count = 100;
    std::string report;  // report file (.pdf, .svg, .png); "" none
    // The face's spelling of the library's field references in the rows' sources, the baseline
    // lines and the warnings (identity when not given).
    std::function<std::string(const std::string&)> spell;

    // The run's settings from the fields (InvalidInput naming the field at fault).
    CompareRunOptions run_options() const;
    // Every check of the settings and of the report path (its format and folder), without the
    // masks: a face calls it before reading them.
    void validate() const;
};

struct CompareReport {
    CompareOutcome outcome;                   // rows of the given masks, then the baselines
    CompareRunOptions options;                // as run
    CompareRequest request;                   // as given, without its masks
    std::vector<std::string> warnings;        // baselines left out and why
    std::vector<std::string> settings_lines;  // the report's settings paragraph
    std::string scenes;                       // the request's scenes, comma-separated
    std::string nsr_words;                    // "NSR tuned per mask" or "NSR 0.01"
    std::string analytic_basis;               // what analytic_wiener_psnr_db is computed on
    std::string mmse_basis;                   // what analytic_mmse_psnr_db is computed on
    // The first mask's gain over the random median on the lead figure, in words ("" without it).
    std::string random_gain_text;
    std::string sim_basis;  // what the simulated PSNR columns are computed on
    // The report's files (path, bytes), not yet written (io/compare_json writes them).
    std::vector<std::pair<std::filesystem::path, std::string>> report_pages;
    std::vector<std::string> report_files;  // written report files (set when written)
    std::string config_file;                // written report config (set when written)
};

// Validates, runs optimize/metrics/compare's run_compare on the request's masks and, with a
// report path, renders the report's pages (report/compare_report).
CompareReport run_compare_request(CompareRequest request, const CompareProgress& progress = {});

}  // namespace pinmask
