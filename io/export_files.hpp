// The export transaction for both faces (`pinmask export` and Python's export_mask): the
// fabrication files of export/pipeline/export_pipeline, each read back from its staged temporary
// (export/pipeline/read_back verify_written; pictures compared with the design,
// export/pipeline/file_check verify_picture), the mask's PSF files (io/psf_files) unless the
// request says no_psf, and the sidecar <stem>.export.json (io/export_sidecar_of), written into
// `out_dir` together or not at all. The faces check the request, the folder and the output names
// before the call (no output may replace the mask file read).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/export_request.hpp"
#include "io/export_sidecar.hpp"

namespace pinmask::io {

struct ExportWritten {
    ExportSummary summary;                   // the layout, its design-rule report, the files
    ExportSidecar sidecar;                   // as written, files and PSF entries included
    std::string sidecar_text;                // <stem>.export.json's bytes
    std::vector<std::filesystem::path> psf;  // the PSF files written (none with no_psf)
};

// One file an export writes: what it is ("" for a fabrication file, "export.json", "PSF", "PSF
// sidecar", "PSF npy") and its path.
struct ExportOutput {
    std::string what;
    std::filesystem::path path;
};

// The stem of an export's files when none is given: the mask file's name without .mask.json
// (or .json), else without its extension.
std::string default_export_stem(const std::filesystem::path& mask_file);

// Every file write_export would write, in the order written (the sidecar first): for the faces to
// check before any work (core/files/output_set).
std::vector<ExportOutput> export_outputs(const ExportRequest& request, const ExportOptions& options,
                                         const std::filesystem::path& out_dir,
                                         const std::string& stem);

// `options` is export_options_from(request, mask, stem). `spell` rewrites the library's notes in
// the sidecar into the face's spelling (unchanged when not given). Throws what export_mask
// throws (nothing written), RuntimeFailure when a file cannot be written or does not read back
// as the design.
ExportWritten write_export(const Mask& mask, const ExportRequest& request,
                           const ExportOptions& options, const std::filesystem::path& out_dir,
                           const std::string& stem,
                           const std::function<std::string(const std::string&)>& spell = {});

}  // namespace pinmask::io
