// PSF files (docs/design.md section 5): a 32-bit float TIFF (optionally also a float32 .npy next to
// it) plus a JSON sidecar with the same stem and extension .json:
//   {"format": "pinmask-psf", "version": 1, "mask_geometry_hash": "<16 hex>", "mask_file": "...",
//    "grid_n": 16, "pixels_per_cell": 8, "pixel_pitch_m": 3e-05,
//    "kernel": {"model": "fresnel", "reason": "...", "wavelengths": [[5.5e-07, 1.0], ...],
//               "enclosed_energy": 0.99, "support_capped": true, "support_px": [129, 129]},
//    "normalisation": "sum=1", "size_px": [rows, cols], "files": {"tiff": "psf.tiff", "npy": ...}}
// ("npy" is absent without --npy; file names are relative to the sidecar's folder). Writing stages
// all files and commits them together (all or nothing). Reading validates the image and, when
// present, the sidecar (format, version, known keys, size).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/files/atomic_file.hpp"
#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask::io {

inline constexpr const char* kPsfFormat = "pinmask-psf";
inline constexpr int kPsfVersion = 1;

struct PsfSidecar {
    std::string mask_geometry_hash;
    std::string mask_file;
    int grid_n = 0;
    int pixels_per_cell = 0;
    double pixel_pitch_m = 0.0;
    std::string kernel_model;  // resolved model
    std::string kernel_reason;
    std::vector<std::pair<double, double>> wavelengths;  // (m, weight), weights sum 1
    double kernel_enclosed_energy = 1.0;
    bool kernel_support_capped = false;
    int kernel_rows = 0, kernel_cols = 0;
    std::string normalisation = "sum=1";
    // "cyclic": the PSF of one period on the torus (rows = cols = grid_n x pixels_per_cell), the
    // integer model the decoder assumes; "full-frame": a linear PSF of any size (exact geometry
    // at an object distance, or a calibrated PSF measured from a point-source capture).
    std::string geometry = "cyclic";
    int rows = 0, cols = 0;
    std::string tiff_file, npy_file;  // names of the image files ("" when absent)
};

// The sidecar fields describing a mask's PSF made with `kernel` (rows, cols and file names are
// filled in by write_psf_files).
PsfSidecar psf_sidecar_for(const Mask& mask, const Kernel& kernel, const std::string& mask_file);

// image.tiff -> image.json (the sidecar of any PSF image path).
std::filesystem::path psf_sidecar_path(const std::filesystem::path& image_path);

nlohmann::ordered_json psf_sidecar_to_json(const PsfSidecar& s);
// Throws InvalidInput naming `where` and the key for a wrong format/version, unknown or missing
// keys and wrong types.
PsfSidecar psf_sidecar_from_json(const nlohmann::json& j, const std::string& where);

// Writes tiff_path (.tif/.tiff, float32), with write_npy also <stem>.npy, and <stem>.json, all or
// nothing. Fills sidecar.rows/cols/tiff_file/npy_file. Returns the paths written. Throws
// InvalidInput for a wrong extension, a missing folder, or a non-finite PSF.
std::vector<std::filesystem::path> write_psf_files(const std::filesystem::path& tiff_path,
                                                   const Plane& psf, PsfSidecar sidecar,
                                                   bool write_npy);

// The same files staged into `files` (core/files/atomic_file), to appear with the group's other
// files or not at all (export's PSF beside its fabrication files). Returns their final paths.
std::vector<std::filesystem::path> stage_psf_files(StagedFiles& files,
                                                   const std::filesystem::path& tiff_path,
                                                   const Plane& psf, PsfSidecar sidecar,
                                                   bool write_npy);

struct PsfFile {
    Plane psf;  // renormalised to sum 1 (float files round the stored sum)
    std::optional<PsfSidecar> sidecar;
};

// Reads a PSF image (TIFF/PNG/npy by content; one channel) and its sidecar when one exists.
// Throws InvalidInput when the image is unreadable, has several channels, holds NaN/Inf or has a
// sum <= 0, or when the sidecar is malformed or its size differs from the image.
PsfFile read_psf_file(const std::filesystem::path& image_path);

}  // namespace pinmask::io
