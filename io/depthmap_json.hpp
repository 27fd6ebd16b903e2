// `pinmask depthmap --json` from the depthmap transaction's result (decode/depthmap/depthmap_run):
// the sources, the settings, the whole-capture and per-map figures, one row per plane and the
// files written. The command prints it and writes it as depthmap.json; Python's depthmap()
// returns it (with the maps as arrays beside it).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "decode/depthmap/depthmap_run.hpp"

namespace pinmask::io {

nlohmann::ordered_json depthmap_json(const DepthmapReport& report);

// The command's text summary: the maps' range, the whole-capture estimate, and with a mask the
// sweep's range and count (given or chosen) and the depth resolution at its ends.
std::string depthmap_text(const DepthmapReport& report);

// The files of a depthmap run in `dir`: depth.tif, confidence.tif, cost_margin.tif,
// all_in_focus.tif (float32), depthmap.png (decode/depthmap/depthmap_picture), depthmap.json.
std::vector<std::filesystem::path> depthmap_file_paths(const std::filesystem::path& dir);

// Writes them all or none (creating dir); sets report.files.
void write_depthmap_files(DepthmapReport& report, const std::filesystem::path& dir);

}  // namespace pinmask::io
