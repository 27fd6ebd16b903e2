#include "cli/options/decode_inputs.hpp"

#include <iostream>
#include <utility>

#include "cli/options/flag_names.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/units.hpp"
#include "design/mask.hpp"
#include "design/psf.hpp"
#include "design/working_distance.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"

namespace pinmask::cli {

using nlohmann::json;

CaptureDecodeInputs load_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                json& stats) {
    if (r.mask.empty() && r.psf.empty()) {
        throw InvalidInput("decode needs the PSF: give --mask FILE.mask.json or --psf FILE");
    }
    Image capture = load_capture(r.capture, bayer, stats);
    CaptureDecodeInputs in = load_shared_inputs(r, bayer, need_counts, stats);
    in.capture = std::move(capture);
    return in;
}

Image load_capture(const std::string& path, BayerMode bayer, json& stats) {
    RawInfo raw;
    LoadedImage loaded = read_capture(path, bayer, &raw);  // RAW: --bayer
    if (!raw.note.empty()) std::cerr << "decode: " << path << ": " << spell_flags(raw.note) << "\n";
    check_image_finite(loaded.image, "capture " + path);
    stats["capture"] = {{"path", path},
                        {"rows", loaded.image.rows()},
                        {"cols", loaded.image.cols()},
                        {"channels", loaded.image.n_channels()},
                        {"full_scale", loaded.full_scale}};
    return std::move(loaded.image);
}

CaptureDecodeInputs load_shared_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                       json& stats) {
    if (r.mask.empty() && r.psf.empty()) {
        throw InvalidInput("decode needs the PSF: give --mask FILE.mask.json or --psf FILE");
    }
    CaptureDecodeInputs in;
    json info;
    if (!r.psf.empty()) {
        io::PsfFile file = io::read_psf_file(r.psf);
        info = {{"source", "psf-file"}, {"path", r.psf}, {"sidecar", file.sidecar.has_value()}};
        if (file.sidecar) {
            info["mask_geometry_hash"] = file.sidecar->mask_geometry_hash;
            info["pixels_per_cell"] = file.sidecar->pixels_per_cell;
            info["kernel_model"] = file.sidecar->kernel_model;
        }
        in.psf = Image(std::move(file.psf));
        if (need_counts) in.psf_counts = read_image(r.psf).image.channels.at(0);
    } else {
        if (need_counts) {
            throw invalid_field("--background", "corner",
                                "needs a measured PSF (--psf): a PSF synthesised from a mask "
                                "has no camera background");
        }
        Mask mask = io::read_mask_file(r.mask);
        if (r.object_distance) {  // refocus: the PSF for an object at u
            const double u =
                parse_length_m(*r.object_distance, "--object-distance", AllowInfinity::kYes);
            check_object_distance(mask.camera, u, "--object-distance");
            mask = mask_at_distance(mask, u);
        }
        in.psf = Image(mask_psf(mask));
        info = {{"source", "mask"},
                {"path", r.mask},
                {"mask_geometry_hash", geometry_hash(mask)},
                {"pixels_per_cell", mask.psf.pixels_per_cell},
                {"kernel_model", mask.psf.kernel.model}};
    }
    check_psf(in.psf.channels[0], "PSF " + (r.psf.empty() ? r.mask : r.psf));
    info["rows"] = in.psf.rows();
    info["cols"] = in.psf.cols();
    stats["psf"] = info;
    if (!r.dark.empty()) {
        in.dark = read_capture(r.dark, bayer).image;
        check_image_finite(*in.dark, "dark frame " + r.dark);
    }
    stats["dark"] =
        in.dark ? json{{"path", r.dark}, {"subtracted", true}} : json{{"subtracted", false}};
    return in;
}

void load_nsr_map(const DecodeCommand& r, DecodeOptions& d, json& stats) {
    if (r.nsr_map.empty()) return;
    LoadedImage map;
    try {
        map = read_image(r.nsr_map);
    } catch (const InvalidInput& e) {
        throw InvalidInput(std::string("--nsr-map: ") + e.what());
    }
    if (map.format != SampleFormat::kFloat32 && map.format != SampleFormat::kFloat64) {
        throw invalid_field("--nsr-map", r.nsr_map,
                            "must hold floating-point values (.npy or float TIFF); an 8/16-bit "
                            "image's values are not NSRs");
    }
    if (map.image.n_channels() != 1) {
        throw invalid_field(
            "--nsr-map", r.nsr_map,
            "must have one channel, it has " + std::to_string(map.image.n_channels()));
    }
    const Plane& nsr = map.image.channels.front();
    if (!is_all_finite(nsr)) {
        throw invalid_field("--nsr-map", r.nsr_map, "holds NaN or Inf; every NSR must be finite");
    }
    if (nsr.size() > 0 && nsr.minCoeff() < 0.0) {
        throw invalid_field("--nsr-map", r.nsr_map,
                            "holds a negative NSR (" + std::to_string(nsr.minCoeff()) +
                                "); every NSR must be >= 0");
    }
    d.wiener.nsr_per_frequency = nsr;
    stats["nsr_map"] = {{"path", r.nsr_map}, {"rows", nsr.rows()}, {"cols", nsr.cols()}};
}

}  // namespace pinmask::cli
