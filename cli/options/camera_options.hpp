// Camera and pattern-geometry flags shared by design, generate, simulate, search: a preset, then
// any parameter overridden with units (`--pinhole 440um`). Parsed once here into design types.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/optics/optics.hpp"
#include "design/pattern/pattern.hpp"

namespace pinmask::cli {

struct CameraOptions {
    std::string preset = "paper";
    bool preset_given = false;    // --preset on the command line (its pinhole is then kept)
    bool default_pinhole = true;  // false: the command solves the pinhole itself
    std::optional<Camera> base;   // used instead of the preset (search --config's "optics")
    std::optional<std::string> camera_file;  // --camera FILE (*.camera.json): replaces the preset
    std::optional<std::string> lens_focal, sensor_distance, object_distance, wavelength, bandwidth,
        pixel_pitch, pinhole, sensor;
};

// --camera FILE, --preset, --lens-focal, --sensor-distance, --object-distance, --wavelength,
// --bandwidth, --pixel-pitch, --pinhole, --sensor WxH.
void add_camera_options(CLI::App& cmd, CameraOptions& o);

// The preset (or --camera FILE, or `base`) with the flag overrides applied, validated
// (InvalidInput naming the flag). A camera of other optics than the paper's (--lens-focal,
// --sensor-distance, --wavelength or --pixel-pitch given, no --preset, --camera or config) without
// --pinhole gets the whole-pixel
// pinhole nearest its diffraction optimum (design/optics/default_pinhole), said on stderr, instead
// of the paper's 440 um.
Camera resolve_camera(const CameraOptions& o);

// True when resolve_camera chose the pinhole (the rule above).
bool pinhole_defaulted(const CameraOptions& o);

// One input of the camera for reports: symbol, value as typed for people, and where it came
// from: "flag", "camera file", "config" or "paper preset default".
struct CameraInput {
    std::string symbol;
    std::string value;
    std::string source;
};
std::vector<CameraInput> camera_inputs(const CameraOptions& o, const Camera& resolved);

// The defaults are the library's: a default PatternGeometry's (the paper's 16, 20, 2) and a
// default Pattern's spacing rule (2 cells).
struct GeometryOptions {
    int grid = PatternGeometry{}.n;
    int holes = PatternGeometry{}.holes;           // K
    int tiles = PatternGeometry{}.tiles_rows;      // tiles per side
    double spacing = Pattern{}.min_spacing_cells;  // min centre spacing, cells
};

// --grid, --holes, --tiles, --spacing. With
// `holes_range` (search), --holes is read as text into it instead: K or a range A..B
// (optimize/search/search_pipeline parse_holes_range), o.holes unused.
void add_geometry_options(CLI::App& cmd, GeometryOptions& o, std::string* holes_range = nullptr);

// The geometry the flags give, each in its range (InvalidInput naming the flag otherwise).
PatternGeometry resolve_geometry(const GeometryOptions& g);

}  // namespace pinmask::cli
