// Text outputs of the error-against-run-time sweep (bench/error_time.hpp): CSV of every record,
// CSV of the scene-averaged curve points, and a Markdown table of the best point per decoder.
// Numbers are written with 6 significant digits; NaN (SSIM of a period below 11 x 11) as "nan".
#pragma once

#include <string>
#include <vector>

#include "bench/error_time.hpp"

namespace pinmask {

// Header: snr_db,scene,decoder,parameter,value,iterations,iterations_run,converged,seconds,
// wall_seconds,timing_runs,psnr_db,ssim; one line per record (seconds = CPU time).
std::string error_time_csv(const std::vector<ErrorTimeRecord>& records);

// Header: snr_db,decoder,parameter,value,iterations,seconds,wall_seconds,psnr_db,ssim,scenes.
std::string error_time_points_csv(const std::vector<ErrorTimePoint>& points);

// A Markdown table per SNR: decoder | setting | iterations | time (s) | PSNR (dB) | SSIM | within
// 0.1 dB of best (iterations, time), one row per decoder (summarise_decoders with kNearBestDb),
// preceded by a "### SNR x dB" heading when there is more than one SNR, and followed by the
// paper's reference timings.
std::string error_time_markdown(const std::vector<DecoderSummary>& summary);

}  // namespace pinmask
