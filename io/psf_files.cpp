#include "io/psf_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <tuple>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/input_file.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io.hpp"
#include "core/units/number_format.hpp"
#include "design/pattern/pattern.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {
namespace {

namespace fs = std::filesystem;
using json_strict::ObjectReader;
using json_strict::read_bool;
using json_strict::read_int;
using json_strict::read_int_pair;
using json_strict::read_number;
using json_strict::read_string;

// A sidecar must describe one PSF the way pinmask writes it; each rule names the field.
void check_consistent(const PsfSidecar& s) {
    using json_strict::fail;
    if (s.grid_n > kMaxGrid)
        fail("grid_n", std::to_string(s.grid_n) + " exceeds " + std::to_string(kMaxGrid));
    if (s.pixels_per_cell > kMaxPixelsPerCell) {
        fail("pixels_per_cell",
             std::to_string(s.pixels_per_cell) + " exceeds " + std::to_string(kMaxPixelsPerCell));
    }
    if (!std::isfinite(s.pixel_pitch_m)) fail("pixel_pitch_m", "must be finite");
    if (s.geometry != "cyclic" && s.geometry != "full-frame")
        fail("geometry", "'" + s.geometry + "' must be cyclic or full-frame");
    const long long side = static_cast<long long>(s.grid_n) * s.pixels_per_cell;
    if (s.geometry == "cyclic" && (s.rows != side || s.cols != side)) {
        fail("size_px", "[" + std::to_string(s.rows) + ", " + std::to_string(s.cols) +
                            "] must be grid_n x pixels_per_cell = " + std::to_string(side) +
                            " per side: the PSF of one period");
    }
    const KernelModel model = parse_kernel_model(s.kernel_model, "kernel.model");
    if (model == KernelModel::kAuto) fail("kernel.model", "must be the resolved model, not auto");
    // A measured kernel (a kernel image, a calibration) has no wavelength of its own.
    if (s.wavelengths.empty() && model != KernelModel::kMeasured)
        fail("kernel.wavelengths", "must name at least one wavelength");
    double weights = 0.0;
    for (const auto& [lambda, w] : s.wavelengths) {
        if (!(lambda > 0.0) || !std::isfinite(lambda)) {
            fail("kernel.wavelengths",
                 format_number(lambda) + " m: a wavelength must be finite and > 0");
        }
        if (!(w >= 0.0) || !std::isfinite(w)) {
            fail("kernel.wavelengths", "weight " + format_number(w) + " must be finite and >= 0");
        }
        weights += w;
    }
    // Weights are written normalised; 1e-6 allows the decimal round trip of a few of them.
    if (!s.wavelengths.empty() && std::fabs(weights - 1.0) > 1e-6) {
        fail("kernel.wavelengths", "weights sum to " + format_number(weights) + ", must sum to 1");
    }
    if (!(s.kernel_enclosed_energy >= 0.0 && s.kernel_enclosed_energy <= 1.0)) {
        fail("kernel.enclosed_energy",
             format_number(s.kernel_enclosed_energy) + " must be in [0, 1]");
    }
    if (s.kernel_rows < 1 || s.kernel_cols < 1 || s.kernel_rows > s.rows ||
        s.kernel_cols > s.cols) {
        fail("kernel.support_px", "[" + std::to_string(s.kernel_rows) + ", " +
                                      std::to_string(s.kernel_cols) +
                                      "] must be >= 1 and at most size_px (the period)");
    }
}

}  // namespace

PsfSidecar psf_sidecar_for(const Mask& mask, const Kernel& kernel, const std::string& mask_file) {
    PsfSidecar s;
    s.mask_geometry_hash = geometry_hash(mask);
    s.mask_file = mask_file;
    s.grid_n = mask.pattern.n;
    s.pixels_per_cell = mask.psf.pixels_per_cell;
    s.pixel_pitch_m = mask.camera.pixel_pitch_m;
    s.kernel_model = kernel_model_name(kernel.model);
    s.kernel_reason = kernel.model_reason;
    s.wavelengths = kernel.wavelengths;
    s.kernel_enclosed_energy = kernel.enclosed_energy;
    s.kernel_support_capped = kernel.support_capped;
    s.kernel_rows = static_cast<int>(kernel.values.rows());
    s.kernel_cols = static_cast<int>(kernel.values.cols());
    return s;
}

fs::path psf_sidecar_path(const fs::path& image_path) {
    fs::path p = image_path;
    return p.replace_extension(".json");
}

nlohmann::ordered_json psf_sidecar_to_json(const PsfSidecar& s) {
    nlohmann::ordered_json wl = nlohmann::ordered_json::array();
    for (const auto& [lambda, weight] : s.wavelengths) wl.push_back({lambda, weight});
    nlohmann::ordered_json files = {{"tiff", s.tiff_file}};
    if (!s.npy_file.empty()) files["npy"] = s.npy_file;
    nlohmann::ordered_json j = {{"format", kPsfFormat},
                                {"version", kPsfVersion},
                                {"mask_geometry_hash", s.mask_geometry_hash},
                                {"mask_file", s.mask_file},
                                {"grid_n", s.grid_n},
                                {"pixels_per_cell", s.pixels_per_cell},
                                {"pixel_pitch_m", s.pixel_pitch_m},
                                {"kernel",
                                 {{"model", s.kernel_model},
                                  {"reason", s.kernel_reason},
                                  {"wavelengths", wl},
                                  {"enclosed_energy", s.kernel_enclosed_energy},
                                  {"support_capped", s.kernel_support_capped},
                                  {"support_px", {s.kernel_rows, s.kernel_cols}}}},
                                {"normalisation", s.normalisation},
                                {"size_px", {s.rows, s.cols}},
                                {"files", files}};
    if (s.geometry != "cyclic") j["geometry"] = s.geometry;  // cyclic sidecars keep their bytes
    return j;
}

PsfSidecar psf_sidecar_from_json(const nlohmann::json& j, const std::string& where) {
    try {
        ObjectReader r(
            j, "",
            {"format", "version", "mask_geometry_hash", "mask_file", "grid_n", "pixels_per_cell",
             "pixel_pitch_m", "kernel", "normalisation", "size_px", "files", "geometry"});
        r.reject_unknown();
        if (read_string(r.required("format"), "format") != kPsfFormat) {
            json_strict::fail("format", std::string("must be \"") + kPsfFormat + "\"");
        }
        const int version = read_int(r.required("version"), "version");
        if (version != kPsfVersion) {
            json_strict::fail("version", std::to_string(version) +
                                             " is not supported (this build reads version " +
                                             std::to_string(kPsfVersion) + ")");
        }
        PsfSidecar s;
        s.mask_geometry_hash = read_string(r.required("mask_geometry_hash"), "mask_geometry_hash");
        s.mask_file = read_string(r.required("mask_file"), "mask_file");
        s.grid_n = read_int(r.required("grid_n"), "grid_n");
        s.pixels_per_cell = read_int(r.required("pixels_per_cell"), "pixels_per_cell");
        if (s.grid_n < 1 || s.pixels_per_cell < 1) {
            json_strict::fail("grid_n", "grid_n and pixels_per_cell must be >= 1");
        }
        s.pixel_pitch_m = read_number(r.required("pixel_pitch_m"), "pixel_pitch_m");
        if (!(s.pixel_pitch_m > 0)) json_strict::fail("pixel_pitch_m", "must be > 0");
        ObjectReader k(
            r.required("kernel"), "kernel",
            {"model", "reason", "wavelengths", "enclosed_energy", "support_capped", "support_px"});
        k.reject_unknown();
        s.kernel_model = read_string(k.required("model"), k.path("model"));
        s.kernel_reason = read_string(k.required("reason"), k.path("reason"));
        const nlohmann::json& wl = k.required("wavelengths");
        if (!wl.is_array()) json_strict::fail(k.path("wavelengths"), "must be an array");
        for (std::size_t i = 0; i < wl.size(); ++i) {
            const std::string path = json_strict::indexed(k.path("wavelengths"), i);
            if (!wl[i].is_array() || wl[i].size() != 2) {
                json_strict::fail(path, "must be [wavelength_m, weight]");
            }
            s.wavelengths.emplace_back(read_number(wl[i][0], json_strict::indexed(path, 0)),
                                       read_number(wl[i][1], json_strict::indexed(path, 1)));
        }
        s.kernel_enclosed_energy =
            read_number(k.required("enclosed_energy"), k.path("enclosed_energy"));
        s.kernel_support_capped = read_bool(k.required("support_capped"), k.path("support_capped"));
        std::tie(s.kernel_rows, s.kernel_cols) =
            read_int_pair(k.required("support_px"), k.path("support_px"), "[rows, cols]");
        s.normalisation = read_string(r.required("normalisation"), "normalisation");
        if (s.normalisation != "sum=1") json_strict::fail("normalisation", "must be \"sum=1\"");
        std::tie(s.rows, s.cols) = read_int_pair(r.required("size_px"), "size_px", "[rows, cols]");
        if (const auto* g = r.optional("geometry")) s.geometry = read_string(*g, "geometry");
        ObjectReader files(r.required("files"), "files", {"tiff", "npy"});
        files.reject_unknown();
        s.tiff_file = read_string(files.required("tiff"), files.path("tiff"));
        if (const auto* npy = files.optional("npy"))
            s.npy_file = read_string(*npy, files.path("npy"));
        check_consistent(s);
        return s;
    } catch (const InvalidInput& e) {
        throw InvalidInput(where + ": " + e.what());
    }
}

std::vector<fs::path> write_psf_files(const fs::path& tiff_path, const Plane& psf,
                                      PsfSidecar sidecar, bool write_npy) {
    StagedFiles files;
    std::vector<fs::path> paths =
        stage_psf_files(files, tiff_path, psf, std::move(sidecar), write_npy);
    files.commit();
    return paths;
}

std::vector<fs::path> stage_psf_files(StagedFiles& files, const fs::path& tiff_path,
                                      const Plane& psf, PsfSidecar sidecar, bool write_npy) {
    const std::string ext = tiff_path.extension().string();
    if (ext != ".tif" && ext != ".tiff") {
        throw invalid_field("-o", tiff_path.string(), "must end in .tif or .tiff");
    }
    const fs::path dir = tiff_path.parent_path();
    if (!dir.empty() && !fs::is_directory(dir)) {
        throw invalid_field("-o", tiff_path.string(), "the output folder does not exist");
    }
    if (psf.size() == 0 || !is_all_finite(psf)) {
        throw InvalidInput("PSF to write is empty or not finite");
    }
    fs::path npy_path = tiff_path;
    npy_path.replace_extension(".npy");
    const fs::path json_path = psf_sidecar_path(tiff_path);
    sidecar.rows = static_cast<int>(psf.rows());
    sidecar.cols = static_cast<int>(psf.cols());
    sidecar.tiff_file = tiff_path.filename().string();
    sidecar.npy_file = write_npy ? npy_path.filename().string() : "";
    const Image image(psf);
    std::vector<fs::path> paths{tiff_path};
    files.stage(tiff_path,
                [&](const fs::path& tmp) { write_tiff(tmp, image, SampleFormat::kFloat32); });
    if (write_npy) {
        files.stage(npy_path, [&](const fs::path& tmp) {
            pinmask::write_npy(tmp, image, SampleFormat::kFloat32);
        });
        paths.push_back(npy_path);
    }
    files.stage_bytes(json_path, json_strict::pretty(psf_sidecar_to_json(sidecar)) + "\n");
    paths.push_back(json_path);
    return paths;
}

PsfFile read_psf_file(const fs::path& image_path) {
    const std::string where = image_path.string();
    const LoadedImage img = read_image(image_path);
    if (img.image.n_channels() != 1) {
        throw InvalidInput(where + ": a PSF file must have one channel, this one has " +
                           std::to_string(img.image.n_channels()));
    }
    PsfFile out;
    out.psf = img.image.channels[0];
    if (!is_all_finite(out.psf)) throw InvalidInput(where + ": the PSF holds NaN or Inf");
    const double sum = out.psf.sum();
    if (std::isinf(sum)) {  // finite values whose sum overflows: dividing would zero the PSF
        throw InvalidInput(where +
                           ": the PSF's values sum beyond the double range; scale them "
                           "down");
    }
    if (!(sum > 0)) {
        throw InvalidInput(where + ": the PSF sums to " + std::to_string(sum) +
                           " (all zeros or negative); it must be > 0");
    }
    out.psf /= sum;
    const fs::path side = psf_sidecar_path(image_path);
    if (side != image_path && fs::exists(side)) {
        if (const auto problem = input_file_problem(side))
            throw InvalidInput(side.string() + ": the PSF's sidecar " + *problem);
        protect_input(side);
        std::ifstream in(side, std::ios::binary);
        std::stringstream buf;
        buf << in.rdbuf();
        nlohmann::json j;
        try {
            j = json_strict::parse_strict(buf.str());
        } catch (const InvalidInput& e) {
            throw InvalidInput(side.string() + ": " + e.what());
        } catch (const nlohmann::json::exception& e) {
            throw InvalidInput(side.string() + ": not valid JSON (" +
                               json_strict::json_error_words(e) + ")");
        }
        out.sidecar = psf_sidecar_from_json(j, side.string());
        if (out.sidecar->rows != out.psf.rows() || out.sidecar->cols != out.psf.cols()) {
            throw InvalidInput(side.string() + ": size_px [" + std::to_string(out.sidecar->rows) +
                               ", " + std::to_string(out.sidecar->cols) +
                               "] differs from the image " + std::to_string(out.psf.rows()) +
                               " x " + std::to_string(out.psf.cols()));
        }
    }
    return out;
}

}  // namespace pinmask::io
