#include "export/formats/read_any.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/name_table.hpp"
#include "core/files/output_set.hpp"
#include "core/limits/resource_limits.hpp"
#include "export/formats/dxf_reader.hpp"
#include "export/formats/gds_reader.hpp"
#include "export/formats/gerber_reader.hpp"
#include "export/formats/oasis_reader.hpp"
#include "export/formats/svg_reader.hpp"

namespace pinmask {

namespace {

// In the order the refusal lists them.
constexpr NameTable<FabFormat, 8> kFabFormatNames{{{FabFormat::kSvg, "svg"},
                                                   {FabFormat::kPdf, "pdf"},
                                                   {FabFormat::kGds, "gds"},
                                                   {FabFormat::kOasis, "oasis"},
                                                   {FabFormat::kDxf, "dxf"},
                                                   {FabFormat::kGerber, "gerber"},
                                                   {FabFormat::kPng, "png"},
                                                   {FabFormat::kTiff1, "tiff1"}}};

}  // namespace

FabFormat parse_fab_format(std::string_view name, std::string_view field) {
    for (const auto& [format, spelled] : kFabFormatNames)
        if (name == spelled) return format;
    throw invalid_field(std::string(field), std::string(name),
                        "must be one of " + names_of(kFabFormatNames, ", "));
}

std::string fab_format_name(FabFormat f) { return name_or(kFabFormatNames, f, "?"); }

std::string fab_extension(FabFormat f) {
    if (f == FabFormat::kGerber) return ".gbr";
    if (f == FabFormat::kOasis) return ".oas";
    if (f == FabFormat::kTiff1) return ".tif";
    return "." + fab_format_name(f);
}

bool is_readable(FabFormat f) {
    return f != FabFormat::kPdf && f != FabFormat::kPng && f != FabFormat::kTiff1;
}

FileGeometry read_fabrication_bytes(std::string_view bytes, FabFormat format) {
    switch (format) {
        case FabFormat::kSvg:
            return read_svg(bytes);
        case FabFormat::kGds:
            return read_gds(bytes);
        case FabFormat::kDxf:
            return read_dxf(bytes);
        case FabFormat::kGerber:
            return read_gerber(bytes);
        case FabFormat::kOasis:
            return read_oasis(bytes);
        default:
            throw invalid_field("format", fab_format_name(format),
                                "has no reader (readable: gds, oasis, dxf, gerber, svg)");
    }
}

std::optional<FabFormat> readable_format_of(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gds" || ext == ".gds2" || ext == ".gdsii") return FabFormat::kGds;
    if (ext == ".oas" || ext == ".oasis") return FabFormat::kOasis;
    if (ext == ".dxf") return FabFormat::kDxf;
    if (ext == ".gbr" || ext == ".ger" || ext == ".gerber") return FabFormat::kGerber;
    if (ext == ".svg") return FabFormat::kSvg;
    return std::nullopt;
}

FileGeometry read_fabrication_file(const std::filesystem::path& path) {
    protect_input(path);  // no output of this run may replace it (core/files/output_set)
    const std::optional<FabFormat> format = readable_format_of(path);
    if (!format)
        throw invalid_field("file", path.string(),
                            "extension must be .gds, .oas, .dxf, .gbr or .svg to be read back");
    const FabFormat f = *format;
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw RuntimeFailure("cannot read " + path.string() + ": " + ec.message());
    check_memory(double(size) * 4.0, "reading " + path.string());
    std::ifstream in(path, std::ios::binary);
    std::string bytes(size, '\0');
    if (!in.read(bytes.data(), std::streamsize(size)))
        throw RuntimeFailure("cannot read " + path.string());
    try {
        return read_fabrication_bytes(bytes, f);
    } catch (const ResourceLimit&) {
        throw;
    } catch (const InvalidInput& e) {
        throw InvalidInput(path.string() + ": " + e.what());
    }
}

}  // namespace pinmask
