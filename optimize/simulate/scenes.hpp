// Test scenes for simulation and scoring: any size (rows x cols), values in [0, 1], the same
// output for the same inputs (and seed). Coordinates: pixel (r, c) covers [r, r+1) x [c, c+1);
// the centre pixel is (floor(rows/2), floor(cols/2)), the PSF-centre convention of decode/.
// Built-ins are one grey channel; a file scene keeps its channels (1 or 3).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image/image.hpp"

namespace pinmask {

enum class SceneKind { kLetterR, kUsaf, kSiemensStar, kChecker, kPoint, kNatural, kFile };

struct SceneSpec {
    SceneKind kind = SceneKind::kNatural;
    std::uint64_t seed = 0;      // natural: the random texture
    double alpha = 1.0;          // natural: amplitude ~ 1/f^alpha (power ~ 1/f^(2 alpha))
    int checker_squares = 8;     // checker: squares across the shorter side
    int star_spokes = 16;        // siemens-star: bright sectors (as many dark)
    std::filesystem::path path;  // file: PNG/TIFF/npy read by core/image/image_io
};

// Names of the built-in scenes, in help order: letter-R, usaf, siemens-star, checker, point,
// natural.
const std::vector<std::string>& builtin_scene_names();

// A built-in name gives that scene (defaults as above); anything else is taken as a file path,
// which must exist (InvalidInput naming the token and the built-in names otherwise).
SceneSpec scene_from_name(const std::string& name);

// The built-in name, or the file path as given.
std::string scene_name(const SceneSpec& spec);

// Renders the scene at rows x cols (both >= 1; InvalidInput otherwise, or for bad parameters).
Image make_scene(const SceneSpec& spec, int rows, int cols);

// A bold sans-serif capital R (Cairo text, fontconfig "sans-serif" bold, unhinted outline,
// anti-aliased with 8-bit coverage) whose ink box fills the frame minus kLetterMargin on each
// side (stretched to the frame's aspect). Letter 1, background 0.
inline constexpr double kLetterMargin = 0.05;  // fraction of each side left empty
Plane letter_r_scene(int rows, int cols);

// USAF-1951-style target: elements of three bars (bar width w, length 5 w, pitch 2 w), each a
// pair of a vertical-bar block and a horizontal-bar block, w shrinking by 2^(-1/2) per element
// from 0.06 of the frame down to 0.0025 of the frame, packed in rows from the top-left. Bars 1,
// background 0, edges exact pixel-area coverage. The layout scales with the frame.
Plane usaf_scene(int rows, int cols);

// Siemens star of `spokes` bright sectors, radius 0.45 min(rows, cols) about the frame centre,
// area-averaged over kStarSupersample^2 sub-pixel samples per pixel.
inline constexpr int kStarSupersample = 8;
Plane siemens_star_scene(int rows, int cols, int spokes);

// Checkerboard of square side min(rows, cols) / squares pixels (real-valued), the square at the
// origin bright, exact pixel-area averages.
Plane checker_scene(int rows, int cols, int squares);

// Zero except 1 at the centre pixel.
Plane point_scene(int rows, int cols);

// Seeded random texture: white Gaussian noise (std::mt19937_64(seed)) shaped in the 2-D DFT by
// amplitude 1/f^alpha, f the periodic radial frequency in cycles per pixel, the mean (f = 0)
// removed, then mapped affinely so its minimum is 0 and maximum 1 (0.5 when constant).
Plane natural_scene(int rows, int cols, std::uint64_t seed, double alpha);

// A page of random words, dark ink on white (optimize/simulate/scene_text.cpp), and a sparse star
// field on black: the --prior families text and stars.
Plane text_scene(int rows, int cols, std::uint64_t seed);
Plane stars_scene(int rows, int cols, std::uint64_t seed);

// An image file, normalised by its full scale (core/image/image_io), resampled to rows x cols by
// exact area averaging. InvalidInput for channel counts other than 1 or 3, non-finite values
// or values outside [0, 1] after normalisation.
Image file_scene(const std::filesystem::path& path, int rows, int cols);

// Exact area-average resampling of a piecewise-constant image: output pixel (r, c) is the mean
// of the input over the footprint [r H/rows, (r+1) H/rows) x [c W/cols, (c+1) W/cols) in input
// pixel units (H x W the input size). Works for shrinking and enlarging; preserves the mean.
Plane resample_area(const Plane& in, int rows, int cols);

}  // namespace pinmask
