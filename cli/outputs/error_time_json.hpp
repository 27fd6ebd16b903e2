// The JSON of `pinmask bench error-time`: error_time.config.json (the resolved configuration)
// and the --json summary on stdout (outputs, best point per decoder, every curve point).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/error_time_run.hpp"

namespace pinmask::cli {

nlohmann::ordered_json error_time_config_json(const Mask& mask, const std::string& source,
                                              const ErrorTimeSetup& setup,
                                              const std::vector<std::string>& scene_names,
                                              const ErrorTimeOptions& et, bool quick);

// `plots`: the written plot paths, SVG then PNG per SNR.
nlohmann::ordered_json error_time_summary_json(const ErrorTimeResult& r,
                                               const std::filesystem::path& out_dir,
                                               const std::vector<std::string>& plots);

}  // namespace pinmask::cli
