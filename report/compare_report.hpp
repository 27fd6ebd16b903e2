// `pinmask compare` results as the plain data of the report library (report/report.hpp): the
// metrics table shared by stdout and page 1, and one page of captioned panels per mask. Used by
// the compare command and the Python module.
#pragma once

#include <string>
#include <vector>

#include "design/optics/camera.hpp"
#include "optimize/metrics/compare.hpp"
#include "report/report.hpp"

namespace pinmask {

// What page 1 says besides the table: the camera and the settings, in words.
struct CompareSummary {
    Camera camera;
    std::vector<std::string> settings_lines;
    std::vector<std::string> baseline_lines;  // what each baseline is, or why it is missing
    std::string noise_text;  // the noise levels in words ("Gaussian noise at SNR 30 dB")
    LeadFigure lead;         // the figure the table leads with, and why
};

// "SNR 30 dB" or "photon model, 2 e per pinhole" (the shown capture's caption).
std::string noise_caption(const NoiseModel& model);

// The metrics table, one row per result (text cells, units in the second header line), led by
// the `lead` figure (optimize/metrics/compare.hpp) and each figure's difference to the first row.
ReportTable compare_table(const std::vector<CompareResult>& results, const std::string& lead);

// The PSNR-against-K view: the masks ordered by pinhole count K with their light gain
// (K times one pinhole's light) and analytic and simulated Wiener PSNR, one line each. Empty
// when all masks have the same K (nothing to compare across K).
std::string compare_holes_text(const std::vector<CompareResult>& results);

// The whole report document.
ReportDocument compare_document(const std::vector<CompareResult>& results,
                                const CompareSettings& settings, const CompareSummary& summary);

}  // namespace pinmask
