// The inputs of `pinmask decode` read from files: the capture, and the inputs every capture of a
// batch shares (the PSF, from a PSF file or synthesised from a mask, its counts for
// --background corner, and the dark frame). Each adds its description to the stats JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cli/options/decode_flags.hpp"
#include "cli/outputs/decode_output.hpp"
#include "core/errors/error.hpp"
#include "core/image/raw_io.hpp"
#include "decode/capture/capture_pipeline.hpp"

namespace pinmask::cli {

// The capture (RAW files through --bayer; with `bayer_given`, any image file as a Bayer mosaic,
// core/image/mosaic.hpp); stats["capture"] describes it; `info` (optional) says how it was
// binned.
Image load_capture(const std::string& path, BayerMode bayer, nlohmann::json& stats,
                   bool bayer_given = false, RawInfo* info = nullptr);

// Refocus (--object-distance with --mask): when the pitch at u is not a whole number of pixels
// (design/optics/working_distance refocus_geometry), the decode uses the exact-geometry PSF at u
// over the whole frame: r.model becomes linear and r.crop none (a note on stderr says so when they
// were set otherwise). Returns true then; false (nothing changed) for a whole pitch or no
// refocus. Call before resolve_request.
bool apply_refocus(DecodeCommand& r);

// The PSF (r.psf or r.mask; `need_counts` keeps a PSF file's own values for --background
// corner) and the dark frame; stats["psf"] and stats["dark"]. The capture is left empty. A
// refocus at a pitch that is not whole synthesises the exact-geometry PSF at u over `frame`
// (rows, cols; 0: the camera's sensor).
CaptureDecodeInputs load_shared_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                       nlohmann::json& stats, int frame_rows = 0,
                                       int frame_cols = 0);

// Both, capture first (as `pinmask decode` reads them). A PSF at the sensor's full resolution
// for a capture read at half resolution is summed 2 x 2 as the capture was, or refused
// (core/image/mosaic.hpp match_psf_to_binned_capture); stderr and stats["psf"]["binned"] say so.
CaptureDecodeInputs load_inputs(const DecodeCommand& r, BayerMode bayer, bool need_counts,
                                nlohmann::json& stats);

// --nsr-map: reads the per-frequency NSR (.npy or float TIFF, one channel, every value finite and
// >= 0; InvalidInput naming --nsr-map and the file otherwise) into d.wiener.nsr_per_frequency;
// stats["nsr_map"] describes it. Nothing when the request has no map.
void load_nsr_map(const DecodeCommand& r, DecodeOptions& d, nlohmann::json& stats);

// Runs `decode` (the pipeline call); an InvalidInput of the decoder about the map (its size is
// checked against the working grid there) is rethrown naming --nsr-map and the file.
template <class F>
auto naming_nsr_map(const DecodeCommand& r, F&& decode) -> decltype(decode()) {
    try {
        return decode();
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        const std::string field = "wiener.nsr_per_frequency";
        const auto at = what.find(field);
        if (r.nsr_map.empty() || at == std::string::npos) throw;
        throw InvalidInput("--nsr-map " + r.nsr_map + ": " + what.substr(0, at) + "the map" +
                           what.substr(at + field.size()));
    }
}

}  // namespace pinmask::cli
