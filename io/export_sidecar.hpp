// The export sidecar `<stem>.export.json` (format "pinmask-export", version 1): what
// `pinmask export` wrote, from which mask, with which layout settings, so that `pinmask check`
// can rebuild the same design from a file alone. Plain data here (no export/ types, io/ stays
// independent of the export library); JSON written with sorted keys (deterministic).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pinmask::io {

struct ExportSidecarFile {
    std::string name;  // file name in the export directory
    std::string format;
    std::string units;
    std::size_t bytes = 0;
    std::string fnv1a64;  // FNV-1a 64 of the bytes, 16 hex digits
    std::string verification;
    std::string detail;  // format-specific ("layer 1/0", "2400 dpi", ...), may be empty
};

struct ExportSidecar {
    // The mask
    std::string mask_path;  // as given to export
    std::string geometry_hash;
    int n = 0, tiles_rows = 1, tiles_cols = 1;
    std::size_t pinholes = 0;
    double pinhole_m = 0.0;
    // The layout settings (what check needs to rebuild the design)
    std::int64_t grid_nm = 1;
    std::string tone = "clear";  // clear | dark
    bool mirrored = false;       // emulsion down
    std::string unit = "um";     // um | mm | in (DXF drawing unit, GDSII/OASIS user unit)
    std::string shape = "square";
    int sides = 8;                   // polygon shape's sides; the sides drawn are in `drawn_sides`
    int drawn_sides = 4;             // sides of each pinhole polygon
    double hole_side_m = 0.0;        // as drawn (after any kerf)
    double chord_tolerance_m = 0.0;  // 0: auto
    double frame_m = 0.0;
    bool marks = false;
    std::vector<std::string> label;  // label lines (empty: none)
    std::size_t max_vertices = 199;
    std::string draw = "film", svg_draw = "polygons", circles = "polygon", hierarchy = "flat";
    double kerf_m = 0.0;
    double png_dpi = 0.0;         // PNG preview resolution (0: unknown, an older sidecar)
    double pdf_margin_m = 10e-3;  // PDF margin around the drawing
    std::array<std::int64_t, 4> active_area_nm{}, extent_nm{};
    std::size_t polygons = 0, annotations = 0;
    // Design-rule check at export
    std::string vendor = "none";
    // The rules the export checked (vendor preset with any min_feature / min_space override), so
    // that `check` applies the same ones; rules_name empty: an older sidecar without them.
    std::string rules_name;
    std::int64_t rules_min_feature_nm = 0, rules_min_space_nm = 1;
    std::size_t rules_max_vertices = 199;
    bool drc_clean = true;
    std::map<std::string, std::size_t> drc_counts;
    std::vector<ExportSidecarFile> files;
    // PSF files (empty: not written; then "psf" records `psf_absent`, why, in the writer's words)
    std::vector<std::string> psf_files;
    std::string psf_absent = "not written";
    std::string psf_kernel;
    int psf_pixels_per_cell = 0, psf_rows = 0, psf_cols = 0;
    std::vector<std::string> notes;
};

// The sidecar's text (pretty JSON, 2-space indent, trailing newline).
std::string export_sidecar_text(const ExportSidecar& s);

// Reads a sidecar. Throws InvalidInput naming the file and the key for a malformed one (wrong
// format or version, missing or mistyped layout keys), RuntimeFailure when it cannot be read.
ExportSidecar read_export_sidecar(const std::filesystem::path& path);

// `<dir>/<stem>.export.json` for a fabrication file `<dir>/<stem>.<ext>`.
std::filesystem::path sidecar_path_for(const std::filesystem::path& file);

}  // namespace pinmask::io
