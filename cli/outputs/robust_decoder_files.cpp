#include "cli/outputs/robust_decoder_files.hpp"

#include <filesystem>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io.hpp"
#include "design/psf/psf.hpp"
#include "io/json_strict.hpp"
#include "io/psf_files.hpp"
#include "optimize/metrics/robust_wiener.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

struct Paths {
    fs::path psf_tiff, psf_npy, sidecar, nsr_npy;
};

Paths paths_in(const fs::path& dir) {
    return {dir / "robust-psf.tiff", dir / "robust-psf.npy", dir / "robust-psf.json",
            dir / "robust-nsr.npy"};
}

}  // namespace

void check_robust_decoder_request(const std::string& dir, const std::vector<std::string>& inputs,
                                  std::size_t noise_levels) {
    if (dir.empty()) throw invalid_field("--robust-decoder", "''", "a folder name is required");
    if (inputs.size() != 1) {
        throw invalid_field("--robust-decoder", dir,
                            "needs exactly one mask (the decoder is the mask's), got " +
                                std::to_string(inputs.size()));
    }
    if (noise_levels != 1) {
        throw invalid_field("--robust-decoder", dir,
                            "needs one noise level (one --snr or --photons value: the filter "
                            "depends on it), got " +
                                std::to_string(noise_levels));
    }
    const fs::path d(dir);
    std::error_code ec;
    if (fs::exists(d, ec) && !fs::is_directory(d, ec))
        throw invalid_field("--robust-decoder", dir, "exists and is not a folder");
    std::vector<NamedPath> in;
    for (const std::string& p : inputs) in.push_back({"mask", p});
    const Paths p = paths_in(d);
    plan_outputs(in, {{"--robust-decoder (psf)", p.psf_tiff, true},
                      {"--robust-decoder (psf npy)", p.psf_npy, true},
                      {"--robust-decoder (psf sidecar)", p.sidecar, true},
                      {"--robust-decoder (nsr)", p.nsr_npy, true}});
}

RobustDecoderFiles write_robust_decoder_files(const std::string& dir, const Mask& mask,
                                              const std::string& mask_path,
                                              const FabricationErrors& errors,
                                              const ScenePrior& prior, const NoiseModel& noise) {
    const RobustWienerModel model(mask, errors, prior, noise);
    const RobustDecoderInputs in = model.robust_decoder_inputs(pattern_spectrum(mask.pattern));
    io::PsfSidecar sidecar = io::psf_sidecar_for(mask, mask_kernel(mask), mask_path);
    sidecar.kernel_reason = "robust decoder: the expected fabricated PSF under " +
                            errors.description() +
                            " (kernel averaged over the size-bias signs, "
                            "times the jitter mean); the design's kernel: " +
                            sidecar.kernel_reason;
    const Paths p = paths_in(dir);
    sidecar.rows = static_cast<int>(in.psf.rows());
    sidecar.cols = static_cast<int>(in.psf.cols());
    sidecar.tiff_file = p.psf_tiff.filename().string();
    sidecar.npy_file = p.psf_npy.filename().string();
    std::error_code ec;
    if (!fs::is_directory(dir, ec) && !fs::create_directories(dir, ec)) {
        throw invalid_field("--robust-decoder", dir, "cannot create the folder: " + ec.message());
    }
    const Image psf(in.psf), nsr(in.nsr);
    StagedFiles files;
    files.stage(p.psf_tiff,
                [&](const fs::path& tmp) { write_tiff(tmp, psf, SampleFormat::kFloat32); });
    files.stage(p.psf_npy,
                [&](const fs::path& tmp) { write_npy(tmp, psf, SampleFormat::kFloat64); });
    files.stage_bytes(p.sidecar, io::json_strict::pretty(io::psf_sidecar_to_json(sidecar)) + "\n");
    files.stage(p.nsr_npy,
                [&](const fs::path& tmp) { write_npy(tmp, nsr, SampleFormat::kFloat64); });
    files.commit();
    return {p.psf_tiff.string(), p.psf_npy.string(), p.sidecar.string(), p.nsr_npy.string(),
            in.floored};
}

std::string robust_decoder_usage(const RobustDecoderFiles& f, const std::string& mask_path) {
    std::string s = "robust decoder of " + mask_path + ": wrote " + f.psf_tiff + ", " + f.psf_npy +
                    ", " + f.sidecar + ", " + f.nsr_npy + "\n  decode a capture with it:\n" +
                    "    pinmask decode CAPTURE --psf " + f.psf_npy + " --nsr-map " + f.nsr_npy +
                    " -o OUT.tiff\n";
    if (f.floored > 0) {
        s += "  note: at " + std::to_string(f.floored) +
             " frequencies decode's deconvwnr floor (1.49e-8) departs from the robust filter\n";
    }
    return s;
}

}  // namespace pinmask::cli
