// A PSF stack for `depthmap --psf-stack`: measured or externally computed PSFs at the candidate
// object distances, in place of the mask's exact geometry.
//
// The file (JSON, at most 1 MiB), or a folder holding it as psf_stack.json:
//   {"format": "pinmask-psf-stack", "version": 1,
//    "planes": [{"object_distance_m": 0.5, "psf": "psf_0.5m.tif"}, ...]}
// 2 to 1000 planes, in any order; object_distance_m a finite number > 0 (metres), the planes'
// distances distinct; psf the path of a one-channel image (float TIFF, .npy, PNG, ...; relative
// paths are relative to the JSON file's folder). Every PSF has the same size, finite,
// non-negative values and a positive sum; it is centred as decode/solvers/psf2otf expects (its
// central element, 0-based (floor(rows / 2), floor(cols / 2)), is the point the capture's light
// comes from) and is normalised to sum 1 by the sweep.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask::io {

inline constexpr const char* kPsfStackFormat = "pinmask-psf-stack";
inline constexpr int kPsfStackVersion = 1;

struct PsfStack {
    std::vector<double> distances_m;           // in the file's order
    std::vector<Plane> psfs;                   // one per distance
    std::vector<std::filesystem::path> files;  // the stack's JSON file, then each PSF's file
};

// Reads and checks the stack. InvalidInput naming `psf_stack`, the path and the rule broken
// (the key path inside the JSON, or the plane and its PSF file); ResourceLimit when the PSFs do
// not fit the memory budget.
PsfStack read_psf_stack(const std::filesystem::path& file_or_dir);

}  // namespace pinmask::io
