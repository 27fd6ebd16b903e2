// The fabrication formats by name and extension, and reading any readable one back
// (GDSII, OASIS, DXF, Gerber, SVG as geometry; PDF, PNG and the 1-bit TIFF are pictures,
// compared with their design by export/pipeline/file_check compare_picture instead).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "export/layout/rings.hpp"

namespace pinmask {

enum class FabFormat { kSvg, kPdf, kGds, kDxf, kGerber, kPng, kOasis, kTiff1 };

// "svg", "pdf", "gds", "dxf", "gerber", "png", "oasis", "tiff1"; anything else throws
// InvalidInput naming `field`.
FabFormat parse_fab_format(std::string_view name, std::string_view field);
std::string fab_format_name(FabFormat f);
// File extension with the dot: .svg .pdf .gds .dxf .gbr .png .oas .tif
std::string fab_extension(FabFormat f);
// True for the formats with a reader.
bool is_readable(FabFormat f);

// Geometry of a file's bytes in a readable format.
FileGeometry read_fabrication_bytes(std::string_view bytes, FabFormat format);

// The readable format of a file name's extension (.gds .gds2 .gdsii .oas .oasis .dxf .gbr .ger
// .gerber .svg, case-insensitive), or nullopt.
std::optional<FabFormat> readable_format_of(const std::filesystem::path& path);

// Reads a file, choosing the reader by extension (.gds .gds2 .gdsii .oas .oasis .dxf .gbr .ger
// .gerber .svg, case-insensitive). Throws InvalidInput for an unknown extension, RuntimeFailure
// when the file cannot be read, ResourceLimit when it is larger than the memory bound.
FileGeometry read_fabrication_file(const std::filesystem::path& path);

}  // namespace pinmask
