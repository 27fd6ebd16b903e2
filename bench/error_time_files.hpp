// The files of `pinmask bench error-time` in its output folder, written together or not at all:
// error_time.csv (every scene and setting), error_time_points.csv (the plotted means),
// error_time.md (best point per decoder), error_time_snrS.svg/.png per SNR and
// error_time.config.json (`config_text`, rendered by the command).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/error_time_run.hpp"

namespace pinmask {

struct ErrorTimeFiles {
    std::vector<std::string> plots;  // the plot paths, SVG then PNG per SNR
    std::size_t count = 0;           // files written
};

// Creates out_dir (its parent must exist).
ErrorTimeFiles write_error_time_files(const std::filesystem::path& out_dir,
                                      const ErrorTimeResult& r, const std::string& config_text);

}  // namespace pinmask
