// `pinmask check` of a fabrication file as a library call: the file's geometry
// (export/formats/read_any) split into pinhole polygons and annotations, compared with its design
// (export/pipeline/read_back) when the design is known, and checked against design rules
// (export/pipeline/drc).
//   with a design and whole_layout (the export sidecar gave every layout setting): every ring
//     and circle is compared with the design's (marks and label included), and the file splits
//     as the design does;
//   with a design only (--mask without a sidecar): rings inside the outline of the design's
//     polygons are the pinholes, compared with the design's polygons;
//   without a design: rings inside `outline` (if given) are the pinholes, all rings otherwise.
//   pictures (PDF, PNG, 1-bit TIFF): no polygons to read; the picture is compared with its
//     design drawn the same way (export/formats/pdf_reader, export/pipeline/raster_check), and the
//     design itself is design-rule checked (check_picture_file).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "export/formats/pdf_writer.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/film_paint.hpp"
#include "export/layout/layout.hpp"
#include "export/layout/rings.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/film_identity.hpp"
#include "export/pipeline/read_back.hpp"

namespace pinmask {

struct FileCheckOptions {
    const Layout* design = nullptr;  // the layout the file was exported from (may be null)
    bool whole_layout = false;       // compare marks and label too (settings from a sidecar)
    std::optional<BoxNm> outline;    // without a design: where the pinholes are
    DrcRules rules;
    double max_xor_nm2 = 0.0;
};

// A picture against its design: what was compared and whether it agrees.
struct PictureComparison {
    std::string method;  // "pixels vs the design rasterised at pixel centres", ...
    std::string result;  // the comparison's describe()
    bool ok = false;
};

struct FileCheck {
    Layout layout;                       // the file as a layout (tone from its info)
    std::optional<ReadBack> comparison;  // with a design
    std::optional<PictureComparison> picture;
    DrcReport drc;
    // What identifies the film (export/pipeline/film_identity): set by the caller, which knows
    // what the export wrote; a mismatch fails the check.
    FilmIdentity identity;
    bool clean() const {
        // (a foreign file without a mask hash is compared by geometry alone)
        return drc.clean() && identity.ok() && (!picture || picture->ok) &&
               (!comparison || (comparison->xor_area_nm2 <= max_xor_nm2 &&
                                (comparison->file_hash.empty() || comparison->hash_ok())));
    }
    double max_xor_nm2 = 0.0;
};

FileCheck check_file_geometry(const FileGeometry& file, const FileCheckOptions& options);

// True for the formats check_picture_file reads (pdf, png, tiff1).
bool is_picture(FabFormat format);

struct PictureCheckOptions {
    DrawMode draw = DrawMode::kFilm;  // PDF and PNG: as export drew them (the sidecar's draw)
    double png_dpi = 0.0;             // PNG: the dpi it was written at (> 0; the sidecar's)
    PdfOptions pdf;                   // PDF: margin (title lines default)
    DrcRules rules;
};

// The picture at `path` in `format` (pdf, png, tiff1) against `design` (as below). Throws
// InvalidInput for an unreadable file, RuntimeFailure when it cannot be read.
PictureComparison compare_picture(const std::filesystem::path& path, FabFormat format,
                                  const Layout& design, const PictureCheckOptions& options);

// Export's verification of a picture it has just written with `written` (draw mode, PNG dpi,
// PDF margin): compare_picture must agree, else RuntimeFailure saying what differs. Returns
// "read back: " and the comparison.
std::string verify_picture(const std::filesystem::path& path, FabFormat format,
                           const Layout& design, const WriteOptions& written);

// Reads the picture at `path` (format by extension: .pdf .png .tif/.tiff) and compares it with
// `design`: 1-bit TIFF pixel for pixel at its own dpi (tolerance 0), PNG within
// kRasterEdgePixels of an edge, PDF ring by ring within kPdfToleranceNm. The design is
// design-rule checked (its layout is the result's). Throws InvalidInput for an unreadable file
// or an unknown extension.
FileCheck check_picture_file(const std::filesystem::path& path, const Layout& design,
                             const PictureCheckOptions& options);

// The picture format of a file name's extension, or nullopt.
std::optional<FabFormat> picture_format_of(const std::filesystem::path& path);

}  // namespace pinmask
