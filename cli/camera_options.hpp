// Camera and pattern-geometry flags shared by design, generate, simulate, search: a preset, then
// any parameter overridden with units (`--pinhole 440um`). Parsed once here into design types.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "design/camera.hpp"

namespace pinmask::cli {

struct CameraOptions {
    std::string preset = "paper";
    std::optional<Camera> base;  // used instead of the preset (search --config's "optics")
    std::optional<std::string> lens_focal, sensor_distance, object_distance, wavelength,
        pixel_pitch, pinhole, sensor;
};

// --preset, --lens-focal, --sensor-distance, --object-distance, --wavelength, --pixel-pitch,
// --pinhole, --sensor WxH.
void add_camera_options(CLI::App& cmd, CameraOptions& o);

// The preset with the overrides applied, validated (InvalidInput naming the flag).
Camera resolve_camera(const CameraOptions& o);

struct GeometryOptions {
    int grid = 16;         // n
    int holes = 20;        // K
    int tiles = 2;         // tiles per side
    double spacing = 2.0;  // min centre spacing, cells
};

// --grid, --holes, --tiles, --spacing (defaults: the paper's 16, 20, 2, 2.0).
void add_geometry_options(CLI::App& cmd, GeometryOptions& o);

}  // namespace pinmask::cli
