// `*.camera.json`: a camera on its own, so a design is typed once and reused by every command
// that takes camera flags (--camera FILE; flags given beside it override its values).
//   {"format": "pinmask-camera", "version": 1, "optics": {...io/optics_json...}}
// Every key is required, unknown keys are refused, the version is checked.
#pragma once

#include <filesystem>
#include <string>

#include "design/optics/camera.hpp"

namespace pinmask::io {

inline constexpr int kCameraFileVersion = 1;

// The file's text (2-space JSON, trailing newline). Validates the camera first.
std::string camera_file_text(const Camera& camera);

// Reads and validates; InvalidInput naming the file, the key and the rule.
Camera read_camera_file(const std::filesystem::path& path);

// Written atomically (temporary name, then renamed).
void write_camera_file(const std::filesystem::path& path, const Camera& camera);

}  // namespace pinmask::io
