// The capture pipeline of `pinmask decode` as one library call: dark frame -> background ->
// 2^K box downsampling -> period check -> crop -> normalisation -> decode each channel (in
// parallel) -> the estimate and a Summary. Never prints, never touches files: the caller loads
// the images and renders the Summary (cli/cmd_decode.cpp, the real-data tests, Python).
//
// Units: with normalize kNone the PSF is scaled to unit sum and the estimate is in capture
// counts; with kL2 the capture window and the PSF are each divided by their L2 norm (the
// DiffuserCam tutorial's preprocessing, decode/capture/preprocess.hpp).
// Precision (kAuto): float32 for every method when the decoded window has at least
// kSinglePrecisionMinPixels pixels, double otherwise. A PSF that float32 cannot hold
// (single_precision_problem, decode/solvers/precision.hpp: values that cancel) runs in double under
// kAuto (a note says why) and is refused under kSingle (InvalidInput, field "precision"). Captures
// of any magnitude are safe: the solvers divide them by their largest magnitude first. Threads:
// FFTW threads for transforms of >= 512 x 512 (core/fft/fft.hpp) and one thread per channel.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/capture/capture.hpp"
#include "decode/capture/capture_defaults.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/capture/period.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "decode/solvers/precision.hpp"

namespace pinmask {

// BackgroundMode, NormalizeMode, Precision and their names: decode/solvers/decode_modes.hpp.

// kSinglePrecisionMinPixels (256 x 256, the rule of --precision auto):
// decode/solvers/precision.hpp.

struct CaptureDecodeOptions {
    CropSpec crop{};  // kCenter: the period centred in the frame
    // Settings read from the data (decode/capture/capture_defaults.hpp) in place of the given
    // crop, decode.model and decode.tv/tvqc.nonnegative; background kAuto likewise. Each choice
    // is recorded in CaptureDecodeSummary::chosen.
    bool crop_auto = false, model_auto = false, nonnegative_auto = false;
    BackgroundMode background = BackgroundMode::kNone;
    double background_value = 0.0;  // kValue: counts off the capture
    int downsample = 0;             // rounds of 2 x 2 averaging, 0..12
    NormalizeMode normalize = NormalizeMode::kNone;
    DecodeOptions decode;  // method, model, parameters
    Precision precision = Precision::kAuto;
    int threads = 0;  // FFTW threads (0: all cores), 1..1024
    // Throws InvalidInput naming the field, its value and the rule.
    void validate() const;
};

struct CaptureDecodeInputs {
    Image capture;                    // one or three channels
    Image psf;                        // one channel (shared) or one per channel
    std::optional<Plane> psf_counts;  // the PSF file's own values (needed by kCorner)
    std::optional<Image> dark;        // same size as the capture; 1 or the capture's channels
    // The PSF is one period of a mask's cyclic tiling (synthesised from a mask, or a PSF file
    // with pinmask's sidecar), not a camera's measured response: the automatic model and
    // background read it so.
    bool psf_one_period = false;
};

struct CaptureDecodeSummary {
    CropWindow window;
    PeriodCheck period;
    std::optional<double> background;      // the value subtracted from the capture
    std::optional<double> psf_background;  // background kAuto: the floor taken off the PSF
    // The settings read from the data (auto), in the order model, crop, background, nonnegative.
    std::vector<ChosenSetting> chosen;
    std::vector<double> capture_l2_norms, psf_l2_norms, psf_sums;
    int decoded_rows = 0, decoded_cols = 0;
    ConvModel model = ConvModel::kCyclic;  // the model decoded with (given or chosen)
    bool single_precision = false;
    int fft_threads = 1;                 // threads the decode's transforms used
    std::vector<DecodeResult> channels;  // per channel, images empty (they are in the estimate)
    bool interrupted = false;
    bool constraint_met = true;      // tvqc: every channel met ||A x - p|| <= eps
    std::vector<std::string> notes;  // what each step decided, one line each (--explain)
    // The channels' DecodeResult::warnings, each once: the faces always show them.
    std::vector<std::string> warnings;
    struct Seconds {
        double dark = 0, preprocess = 0, period_check = 0, crop = 0, decode = 0;
        double fft_planning = 0;  // FFT planning during the decode (measuring, or wisdom)
    } seconds;
};

struct CaptureDecodeResult {
    Image estimate;
    CaptureDecodeSummary summary;
};

// Runs the pipeline. Throws InvalidInput for bad inputs or options (naming the field),
// RuntimeFailure when a solver returns a non-finite estimate.
CaptureDecodeResult decode_capture(CaptureDecodeInputs inputs, const CaptureDecodeOptions& options);

}  // namespace pinmask
