// The capture pipeline of `pinmask decode` as one library call: dark frame -> background ->
// 2^K box downsampling -> model -> period check -> crop -> method -> normalisation -> decode each
// channel (in parallel) -> the estimate and a Summary. In two steps when the caller needs the
// method before the decode runs (progress for an iterative method, the Python module's thread):
// prepare_capture, then decode_prepared. Never prints, never touches files: the caller loads
// the images and renders the Summary (cli/cmd_decode.cpp, the real-data tests, Python).
//
// Units: with normalize kNone the PSF is scaled to unit sum and the estimate is in capture
// counts; with kL2 the capture window and the PSF are each divided by their L2 norm (the
// DiffuserCam tutorial's preprocessing, decode/capture/preprocess.hpp). Each is one factor over
// its channels (the root mean square of their norms, the mean of their sums): the channels of
// a colour capture keep their ratios.
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
    // crop, decode.model, decode.method and decode.tv/tvqc.nonnegative; background kAuto
    // likewise. Each choice is recorded in CaptureDecodeSummary::chosen. method_auto chooses
    // wiener or tv (auto_method_is_tv) after the model and the crop, and reads the parameters
    // of whichever it chooses from decode.wiener, decode.tv and decode.iterative (so both are
    // filled and validated).
    bool crop_auto = false, model_auto = false, method_auto = false, nonnegative_auto = false;
    // The method was not given but implied by a parameter only it reads (the request's field,
    // e.g. "nsr"): recorded in CaptureDecodeSummary::chosen as the method's reason. Empty
    // otherwise.
    std::string method_implied_by;
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
    // The settings read from the data (auto), in the order background, model, crop, method,
    // nonnegative.
    std::vector<ChosenSetting> chosen;
    std::vector<double> capture_l2_norms, psf_l2_norms, psf_sums;
    int decoded_rows = 0, decoded_cols = 0;
    ConvModel model = ConvModel::kCyclic;         // the model decoded with (given or chosen)
    DecodeMethod method = DecodeMethod::kWiener;  // the method decoded with (given or chosen)
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

// Everything before the decode: the capture window and the PSF as the solvers will read them,
// the options with every automatic setting resolved (decode.method is the method that will run),
// and the summary so far. The caller may set decode.iterative.stop and iterations_done here.
struct PreparedCapture {
    Image capture;
    std::vector<Plane> psf;
    DecodeOptions decode;
    CaptureDecodeSummary summary;
    // Each channel's noise sigma measured on the capture before downsampling (empty: the
    // solvers measure it on the window they decode).
    std::vector<double> noise_sigmas;
};

// The pipeline up to the decode. Throws InvalidInput for bad inputs or options (naming the field).
PreparedCapture prepare_capture(CaptureDecodeInputs inputs, const CaptureDecodeOptions& options);
// The decode of each channel and the estimate. Throws RuntimeFailure when a solver returns a
// non-finite estimate.
CaptureDecodeResult decode_prepared(PreparedCapture prepared);

// Runs the pipeline: decode_prepared(prepare_capture(inputs, options)).
CaptureDecodeResult decode_capture(CaptureDecodeInputs inputs, const CaptureDecodeOptions& options);

}  // namespace pinmask
