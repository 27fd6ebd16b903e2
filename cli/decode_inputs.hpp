// The inputs of `pinmask decode` read from files: the capture, and the inputs every capture of a
// batch shares (the PSF, from a PSF file or synthesised from a mask, its counts for
// --background corner, and the dark frame). Each adds its description to the stats JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cli/decode_output.hpp"
#include "core/raw_io.hpp"
#include "decode/capture_pipeline.hpp"

namespace pinmask::cli {

// The capture (RAW files through --bayer); stats["capture"] describes it.
Image load_capture(const std::string& path, BayerMode bayer, nlohmann::json& stats);

// The PSF (r.psf or r.mask; `need_counts` keeps a PSF file's own values for --background
// corner) and the dark frame; stats["psf"] and stats["dark"]. The capture is left empty.
CaptureDecodeInputs load_shared_inputs(const DecodeRequest& r, BayerMode bayer, bool need_counts,
                                       nlohmann::json& stats);

// Both, capture first (as `pinmask decode` reads them).
CaptureDecodeInputs load_inputs(const DecodeRequest& r, BayerMode bayer, bool need_counts,
                                nlohmann::json& stats);

}  // namespace pinmask::cli
