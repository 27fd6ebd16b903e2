#include "io/export_files.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "design/psf/psf.hpp"
#include "export/pipeline/file_check.hpp"
#include "export/pipeline/read_back.hpp"
#include "io/export_sidecar_of.hpp"
#include "io/psf_files.hpp"

namespace pinmask::io {

namespace fs = std::filesystem;

namespace {

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) throw RuntimeFailure("cannot read back " + p.string());
    return s.str();
}

}  // namespace

std::string default_export_stem(const std::filesystem::path& mask_file) {
    const std::string name = mask_file.filename().string();
    for (const std::string suffix : {".mask.json", ".json"})
        if (name.size() > suffix.size() && name.ends_with(suffix))
            return name.substr(0, name.size() - suffix.size());
    return mask_file.stem().string();
}

std::vector<ExportOutput> export_outputs(const ExportRequest& f, const ExportOptions& o,
                                         const fs::path& out_dir, const std::string& stem) {
    std::vector<ExportOutput> outs{{"export.json", out_dir / (stem + ".export.json")}};
    for (FabFormat ff : o.formats) outs.push_back({"", out_dir / (stem + fab_extension(ff))});
    if (!f.no_psf) {
        const fs::path psf_tiff = out_dir / (stem + ".psf.tiff");
        outs.push_back({"PSF", psf_tiff});
        outs.push_back({"PSF sidecar", psf_sidecar_path(psf_tiff)});
        if (f.psf_npy) outs.push_back({"PSF npy", out_dir / (stem + ".psf.npy")});
    }
    return outs;
}

ExportWritten write_export(const Mask& mask, const ExportRequest& f, const ExportOptions& o,
                           const fs::path& out_dir, const std::string& stem,
                           const std::function<std::string(const std::string&)>& spell) {
    ExportWritten w;
    w.summary = export_mask(mask, o);
    const ExportSummary& s = w.summary;
    ExportSidecar& side = w.sidecar;
    side = export_sidecar_of(f, mask, o, s);
    if (spell)
        for (std::string& n : side.notes) n = spell(n);
    std::optional<std::pair<Plane, PsfSidecar>> psf;
    if (!f.no_psf) {
        check_psf_memory(mask.pattern.n, mask.psf.pixels_per_cell, 2, 0);
        const Kernel kernel = mask_kernel(mask);
        psf.emplace(synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell),
                    psf_sidecar_for(mask, kernel, f.input));
    }
    fs::create_directories(out_dir);
    StagedFiles staged;
    for (const ExportedFile& e : s.files) {
        const fs::path path = out_dir / (stem + e.extension);
        std::string check = "not readable (written only)";
        staged.stage(path, [&](const fs::path& tmp) {
            {
                std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
                out.write(e.bytes.data(), std::streamsize(e.bytes.size()));
                out.close();  // a failed flush (disk full, file-size limit) shows here
                if (!out)
                    throw RuntimeFailure("cannot write " + tmp.string() + ": " +
                                         std::strerror(errno));
            }
            if (is_readable(e.format)) check = verify_written(file_bytes(tmp), e.format, s.layout);
            if (is_picture(e.format)) check = verify_picture(tmp, e.format, s.layout, o.write);
        });
        side.files.push_back(sidecar_file_entry(path.filename().string(), e, check, f, o));
    }
    if (psf) {  // staged with the others: all appear, or none
        w.psf = stage_psf_files(staged, out_dir / (stem + ".psf.tiff"), psf->first, psf->second,
                                f.psf_npy);
        for (const fs::path& p : w.psf) side.psf_files.push_back(p.filename().string());
        side.psf_kernel = psf->second.kernel_model;
        side.psf_pixels_per_cell = psf->second.pixels_per_cell;
        side.psf_rows = int(psf->first.rows());
        side.psf_cols = int(psf->first.cols());
    }
    w.sidecar_text = export_sidecar_text(side);
    staged.stage_bytes(out_dir / (stem + ".export.json"), w.sidecar_text);
    staged.commit();
    return w;
}

}  // namespace pinmask::io
