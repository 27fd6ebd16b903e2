// The sweep file of `pinmask sweep SWEEP.json`: a base search configuration (the keys of
// search.config.json, io/search_config.hpp) and the design points, as a grid or as a list:
//   {"format": "pinmask-sweep", "version": 1,
//    "base": {search config keys; "format"/"version" may be left out},
//    "grid": {"holes": [8, 12, 16], "optics.pinhole_m": [3e-4, 4.4e-4], "noise.snr_db": [20, 30]}}
// or, instead of "grid", "points": [{"holes": 8}, {"holes": 12, "noise.snr_db": 20}].
// A key is a dotted path into the search configuration ("noise.photons_per_pinhole",
// "optics.pinhole_m", "prior.family", "seed", ...): any search option may vary. The grid is the
// Cartesian product over the keys in alphabetical order, the last varying fastest. Every point is
// the base with its values set, parsed by the search-config codec: a bad point is refused before
// any search starts.
// Sweep rules on top of the search codec's: exactly one of "grid" and "points"; a grid key has
// a non-empty list; "format", "version", "generator", "kernel_resolved" and "time" cannot vary;
// every point has an evaluation budget (evaluations_per_chain >= 1: points are reproducible); a
// varied "optics.*" key needs a complete base "optics" object; "noise.snr_db" belongs to the
// Gaussian model, "noise.photons_per_pinhole" and the sensor keys to the photon model; "threads"
// defaults to 1 per point (a rank's search) and cannot be 0 (all cores), so results do not
// depend on the machine. Errors are InvalidInput naming the key path ("grid.holes: ...", or
// "grid point 3 (holes = 0): holes: 0 must be >= 1" for a value the search codec refuses).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/search_config.hpp"

namespace pinmask::io {

inline constexpr const char* kSweepFormat = "pinmask-sweep";
inline constexpr int kSweepVersion = 1;
// A sweep of more points than this is a mistake in the file (each point is one whole search).
inline constexpr std::size_t kMaxSweepPoints = 10000;

// One varied key of one point: its path, its value as written ("8", "3e-4", "photon"), and the
// value as a number when it is one (for tables and plots).
struct SweepValue {
    std::string key, text;
    std::optional<double> number;
};

struct SweepPoint {
    std::vector<SweepValue> values;  // in the order of SweepConfig::keys
    SearchConfig config;             // the base with this point's values, parsed
    std::string config_text;         // that configuration as JSON (the point's resolved file)
};

struct SweepConfig {
    std::vector<std::string> keys;  // the varied keys, alphabetical
    std::vector<SweepPoint> points;
    std::string text;  // the sweep file as parsed, pretty-printed
};

// Parses the text of a sweep file (see above); InvalidInput naming the key path on any problem.
SweepConfig parse_sweep_config(const std::string& text);

// Reads `path`: InvalidInput naming the file when it cannot be read or parsed.
SweepConfig read_sweep_config(const std::filesystem::path& path);

}  // namespace pinmask::io
