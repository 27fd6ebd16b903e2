// `pinmask compare --json` from the compare transaction's result (report/compare_run): the rows
// (score's keys for every noise level, io/metrics_json.hpp, and each row's difference_to_first),
// the lead figure and why, what each PSNR column is computed on, the settings, the baselines
// (the random median with its standard error and the first mask's gain over it) and, once
// written, the report's files. The command prints it, writes it as the
// report's config, and the Python module's compare() returns it as a dict.
#pragma once

#include <nlohmann/json.hpp>

#include "optimize/metrics/compare.hpp"
#include "report/compare_run.hpp"

namespace pinmask::io {

// One row: the table figures plus every noise level under score's keys (infinities as null).
nlohmann::ordered_json compare_row_json(const CompareRow& row);

nlohmann::ordered_json compare_json(const CompareReport& report);

// Writes the report's pages and, beside them, NAME.config.json (compare_json with the files),
// all or none; sets report_files and config_file. Nothing without report pages.
void write_compare_report(CompareReport& report);

// The config file beside a report at `report_path` ("dir/r.pdf" -> "dir/r.config.json").
std::filesystem::path compare_config_path(const std::filesystem::path& report_path);

}  // namespace pinmask::io
