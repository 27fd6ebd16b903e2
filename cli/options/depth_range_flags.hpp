// The depth range flags --depth-from/--depth-to of score, compare and search: one registration
// and one rule for the three commands. The values are lengths with units like every distance
// flag ("0.4m", "400mm"; a plain number is metres, core/units/units), converted before CLI11 stores
// them, so the variables stay doubles in metres and a config file's plain number still merges
// into them (search --config).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "optimize/metrics/depth_fisher.hpp"

namespace pinmask::cli {

// Registers --depth-from and --depth-to on `cmd`, stored in metres (0: unset, the working
// distance / 2 .. x 2). `with` names what turns the depth figure on, for the help ("--metrics
// depth", "--depth", "--depth-weight").
void add_depth_range_flags(CLI::App& cmd, double& from_m, double& to_m, const std::string& with);

// The range as given, after refusing --depth-from/--depth-to when the depth figure is off
// (`depth_on` false): `add` says how to turn it on.
DepthRange depth_range_of(const CLI::App& cmd, double from_m, double to_m, bool depth_on,
                          const std::string& add);

}  // namespace pinmask::cli
