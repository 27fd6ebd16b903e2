#include "cli/options/decode_inputs.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <utility>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "core/image/mosaic.hpp"
#include "core/units/units.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"

namespace pinmask::cli {

using nlohmann::json;

CaptureDecodeInputs load_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                json& stats) {
    if (r.mask.empty() && r.psf.empty()) {
        throw InvalidInput("decode needs the PSF: give --mask FILE.mask.json or --psf FILE");
    }
    RawInfo raw;
    Image capture = load_capture(r.capture, bayer, stats, r.bayer_given, &raw);
    CaptureDecodeInputs in =
        load_shared_inputs(r, bayer, need_counts, stats, static_cast<int>(capture.rows()),
                           static_cast<int>(capture.cols()));
    std::string note;
    for (Plane& p : in.psf.channels)
        match_psf_to_binned_capture(p, capture.rows(), capture.cols(), raw, note);
    if (in.psf_counts)
        match_psf_to_binned_capture(*in.psf_counts, capture.rows(), capture.cols(), raw, note);
    if (!note.empty()) {
        std::cerr << "decode: " << spell_flags(note) << "\n";
        stats["psf"]["binned"] = spell_flags(note);
    }
    in.capture = std::move(capture);
    return in;
}

Image load_capture(const std::string& path, BayerMode bayer, json& stats, bool bayer_given,
                   RawInfo* info) {
    RawInfo raw;
    // RAW: --bayer; another image file only when --bayer is given (a mosaic saved as an image).
    LoadedImage loaded =
        bayer_given ? read_capture_as_mosaic(path, bayer, &raw) : read_capture(path, bayer, &raw);
    if (info) *info = raw;
    if (!raw.note.empty()) std::cerr << "decode: " << path << ": " << spell_flags(raw.note) << "\n";
    check_image_finite(loaded.image, "capture " + path);
    stats["capture"] = {{"path", path},
                        {"rows", loaded.image.rows()},
                        {"cols", loaded.image.cols()},
                        {"channels", loaded.image.n_channels()},
                        {"full_scale", loaded.full_scale}};
    return std::move(loaded.image);
}

namespace {

double refocus_distance(const DecodeCommand& r, const Mask& mask) {
    const double u = parse_length_m(*r.object_distance, "--object-distance", AllowInfinity::kYes);
    check_object_distance(mask.camera, u, "--object-distance");
    return u;
}

}  // namespace

bool apply_refocus(DecodeCommand& r) {
    if (!r.object_distance || r.mask.empty()) return false;
    const Mask mask = io::read_mask_file(r.mask);
    const RefocusGeometry g = refocus_geometry(mask, refocus_distance(r, mask));
    if (!g.exact_geometry) return false;
    if ((r.model != "linear" && r.model != "auto") || (r.crop != "none" && r.crop != "auto"))
        std::cerr << "decode: --object-distance " << *r.object_distance << ": the pitch there is "
                  << g.pitch_px << " px per cell, not a whole number (" << g.mismatch_px
                  << " px off across one period): decoding the whole frame with the exact-geometry "
                     "PSF at that distance (--model linear --crop none)\n";
    r.model = "linear";
    r.crop = "none";
    return true;
}

CaptureDecodeInputs load_shared_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                       json& stats, int frame_rows, int frame_cols) {
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
        // pinmask's own PSF file is one period of a mask's tiling when its sidecar says
        // "cyclic"; a "full-frame" one (exact geometry, calibrate's psf.tiff) is a response over
        // the sensor, like a measured PSF.
        in.psf_one_period = file.sidecar && file.sidecar->geometry == "cyclic";
        // Background auto reads a measured PSF's own values only (pinmask's has no floor).
        if (need_counts && (r.request.background.mode == BackgroundMode::kCorner || !file.sidecar))
            in.psf_counts = read_image(r.psf).image.channels.at(0);
    } else {
        if (r.request.background.mode == BackgroundMode::kCorner) {
            throw invalid_field("--background", "corner",
                                "needs a measured PSF (--psf): a PSF synthesised from a mask "
                                "has no camera background");
        }
        Mask mask = io::read_mask_file(r.mask);
        in.psf_one_period = true;
        std::optional<RefocusGeometry> refocus;
        double u = mask.camera.object_distance_m;
        if (r.object_distance) {  // refocus: the PSF for an object at u
            u = refocus_distance(r, mask);
            refocus = refocus_geometry(mask, u);
        }
        if (refocus && refocus->exact_geometry) {
            // The pitch at u is not whole: what the sensor records from a point at u, over the
            // frame (design/psf/psf_exact), for the linear model (apply_refocus set it).
            ExactPsfOptions eo;
            eo.object_distance_m = u;
            eo.rows = frame_rows;
            eo.cols = frame_cols;
            in.psf = Image(exact_psf(mask, eo));
        } else {
            if (refocus) mask = mask_at_distance(mask, u);
            in.psf = Image(mask_psf(mask));
        }
        info = {{"source", "mask"},
                {"path", r.mask},
                {"mask_geometry_hash", geometry_hash(mask)},
                {"pixels_per_cell", mask.psf.pixels_per_cell},
                {"kernel_model", mask.psf.kernel.model}};
        if (refocus)
            info["refocus"] = {{"object_distance_m", std::isinf(u) ? json("inf") : json(u)},
                               {"pitch_px", refocus->pitch_px},
                               {"whole_pixels_per_cell", refocus->whole_px},
                               {"mismatch_px", refocus->mismatch_px},
                               {"geometry", refocus->exact_geometry ? "exact" : "integer"}};
    }
    check_psf(in.psf.channels[0], "PSF " + (r.psf.empty() ? r.mask : r.psf));
    info["rows"] = in.psf.rows();
    info["cols"] = in.psf.cols();
    stats["psf"] = info;
    if (!r.dark.empty()) {
        in.dark =
            (r.bayer_given ? read_capture_as_mosaic(r.dark, bayer) : read_capture(r.dark, bayer))
                .image;
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
