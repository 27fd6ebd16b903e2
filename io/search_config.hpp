// The search configuration file, `search.config.json`: `pinmask search` writes the resolved
// settings of every run there, and `pinmask search --config FILE` reads one back to repeat or
// vary the run (options given on the command line win). A hand-written file may hold any subset
// of the keys; "format" and "version" are required. Layout (all optional but the first two):
//   {"format": "pinmask-search-config", "version": 1, "generator" (informational),
//    "strategy": "random" | "anneal", "time": "20s" (null: an --evals run, no time budget),
//    "evaluations_per_chain": >= 0 (0: --time), "ranks": >= 1 (MPI ranks of the run that wrote
//    it: the chains and islands depend on it),
//    "threads": >= 0, "seed": >= 0, "top": >= 1, "grid", "holes", "tiles" (integers >= 1),
//    "max_holes": >= 0 (0: K fixed at "holes"; else the range holes..max_holes),
//    "min_spacing_cells": > 0, "keep_out": "none" | "border", "pixels_per_cell": >= 1,
//    "kernel_requested": auto | box | fraunhofer | fresnel | paper-fig3b | measured,
//    "kernel_resolved" (informational), "kernel_path": file of --kernel measured,
//    "noise": {"model": "gaussian", "snr_db"} or {"model": "photon", "photons_per_pinhole",
//              "read_noise_e", "dark_current_e", "full_well_e" (null: none), "adc_bits",
//              "film_optical_density" (null: opaque)}, "filter": "optimal" | "nsr:VALUE",
//    "prior": {"family": "natural" | "text" | "stars" | "files", "scenes": >= 1,
//              "files": [paths]}, "allow_spectral_zeros": bool, "rank_by": "wiener" | "tv",
//    "weights": {"analytic_wiener", "max_sidelobe", "sidelobe_energy", "min_spectrum",
//                "depth" (written only when > 0)},
//    "depth_range": {"from_m", "to_m"} (metres, 0 and 0: the working distance / 2 .. x 2;
//                written only with a depth weight),
//    "rerank_scenes": [names] ([]: no re-ranking), "rerank_tv": bool,
//    "optics": the camera (io/optics_json.hpp)}
// Unknown keys, repeated keys, wrong types and out-of-range values are InvalidInput naming the
// key path; so is nesting deeper than json_strict allows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/version.hpp"
#include "design/optics/camera.hpp"

namespace pinmask::io {

// The generator string of a search run (its masks' provenance and its resolved configuration).
inline constexpr const char* kSearchGenerator = PINMASK_GENERATOR("search");

inline constexpr const char* kSearchConfigFormat = "pinmask-search-config";
inline constexpr int kSearchConfigVersion = 1;

// What a configuration file sets; an empty optional leaves the option to its default (or to the
// command line).
struct SearchConfig {
    std::optional<std::string> strategy, time, keep_out, kernel, kernel_path, filter;
    std::optional<std::int64_t> evaluations_per_chain;
    std::optional<int> threads, top, grid, holes, max_holes, tiles, pixels_per_cell, prior_scenes;
    std::optional<int> ranks;  // of the run that wrote the file (informational; checked)
    std::optional<std::uint64_t> seed;
    std::optional<double> min_spacing_cells, snr_db;
    std::optional<double> w_analytic, w_max_sidelobe, w_sidelobe_energy, w_min_spectrum, w_depth;
    std::optional<double> depth_from, depth_to;  // "depth_range"
    std::optional<std::vector<std::string>> rerank_scenes;
    std::optional<bool> rerank_tv;
    std::optional<Camera> optics;
    // The photon model (noise.model "photon"); full_well and optical_density may be +inf.
    std::optional<double> photons, read_noise, dark_current, full_well, optical_density;
    std::optional<int> bits;
    std::optional<std::string> prior_family, rank_by;
    // The design objective: "objective": "nominal" | "robust", "robust": the fabrication
    // errors in the text form of optimize/metrics/robust_errors (size=5um,jitter=2um,missing=0.01).
    std::optional<std::string> objective, robust;
    std::optional<std::vector<std::string>> prior_files;
    std::optional<bool> allow_spectral_zeros;
};

// Parses the text of a configuration file: InvalidInput on any problem (see above), JSON syntax
// and number overflow included.
SearchConfig parse_search_config(const std::string& text);

// Reads `path` (InvalidInput naming the file when it cannot be read or parsed).
SearchConfig read_search_config(const std::filesystem::path& path);

}  // namespace pinmask::io
