// Output side of `pinmask decode`: its request (the options as given on the command line, also
// written back as the resolved configuration), the output format chosen by extension, the
// scaling of the estimate for PNG, the JSON of the period check, and the warning text for a
// period mismatch.
//
// PNG scaling (documented in `pinmask decode --help`): negative values are clipped to 0, then
// every channel is multiplied by one factor: 1 / (the maximum over all channels) by default,
// or the --scale value; results above 1 clip to full white. TIFF and .npy hold the raw float32
// estimate (capture units), unscaled.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image.hpp"
#include "decode/capture.hpp"
#include "decode/capture_pipeline.hpp"
#include "decode/decoder.hpp"
#include "decode/period.hpp"

namespace pinmask::cli {

// Every flag of `pinmask decode`, with its default (see --help for meanings and units).
struct DecodeRequest {
    std::string capture, mask, psf, dark;
    // --object-distance: refocus the mask's PSF to an object at this distance.
    std::optional<std::string> object_distance;
    std::string crop = "center";    // center | none | X,Y
    std::string method = "wiener";  // decode/decode_method.hpp names
    std::string model = "cyclic";
    double nsr = 0.01;
    double lambda = 1e-3;
    std::string regulariser = "identity";
    std::optional<double> eps, noise_sigma;
    bool nonnegative = false;
    int iterations = 200;
    double tolerance = 1e-4;
    int downsample = 0;
    std::string background = "none";  // none | corner | VALUE
    std::string normalize = "none";   // none | l2
    std::string output;
    int bits = 8;
    std::string scale = "max";  // max | VALUE
    std::string stats;
    bool json = false;
    bool explain = false;
    int threads = 0;                 // 0: all cores
    std::string precision = "auto";  // auto | single | double
};

// --crop: center (or centre) | none | X,Y (integer top-left column, row). InvalidInput otherwise.
CropSpec parse_crop(const std::string& text);

// The flags that set a parameter of one method's struct in DecodeOptions (decode/decoder.hpp).
enum class MethodFlag {
    kNsr,          // wiener.nsr
    kLambda,       // tikhonov.lambda, tv.lambda
    kRegulariser,  // tikhonov.regulariser
    kEps,          // tvqc.eps
    kNoiseSigma,   // tvqc.noise_sigma
    kNonnegative,  // tv.nonnegative, tvqc.nonnegative
    kIterations,   // iterative.max_iterations (tv, tvqc, richardson-lucy)
    kTolerance,    // iterative.tolerance (tv, tvqc, richardson-lucy)
};
inline constexpr MethodFlag kMethodFlags[] = {MethodFlag::kNsr,         MethodFlag::kLambda,
                                              MethodFlag::kRegulariser, MethodFlag::kEps,
                                              MethodFlag::kNoiseSigma,  MethodFlag::kNonnegative,
                                              MethodFlag::kIterations,  MethodFlag::kTolerance};
// "--nsr", "--lambda", ... (the CLI's spelling).
const char* method_flag_name(MethodFlag flag);

// Writes the request's value for `flag` into the options of d.method that hold that parameter;
// false when that method has no such parameter (its value would be dropped). The one place
// that says which flag goes where: decode_options and the refusals below both use it.
bool write_method_flag(DecodeOptions& d, MethodFlag flag, const DecodeRequest& request);

// A flag given (the CLI's count, Python's non-None arguments) with its value as text.
struct GivenFlag {
    MethodFlag flag;
    std::string value;
};
// InvalidInput (exit 2) naming the first given flag that the request's method does not read
// and the methods that do; then the refusal of --lambda <= 0 for tikhonov.
void refuse_unused_flags(const DecodeRequest& request, const std::vector<GivenFlag>& given);

// The DecodeOptions of a request: method (unknown names refused), model, and every parameter
// the chosen method reads (write_method_flag).
DecodeOptions decode_options(const DecodeRequest& request);
// The pipeline options of a request (crop, background, downsample, normalize, decode,
// precision, threads).
CaptureDecodeOptions capture_decode_options(const DecodeRequest& request);

// Adds the pipeline's results to the stats JSON and its timings to `timings`. Everything
// outside "timings_s" is deterministic (same inputs and options: the same bytes); all
// wall-clock figures (per stage, per channel, per iteration) go to `timings`.
void add_summary_json(nlohmann::json& stats, nlohmann::json& timings, const DecodeRequest& request,
                      const CaptureDecodeSummary& summary);

// --background: none | corner | a number of counts (mode "value").
struct Background {
    BackgroundMode mode = BackgroundMode::kNone;
    double value = 0.0;
};
Background parse_background(const std::string& text);

// --scale: "max" -> empty; a factor > 0 otherwise (InvalidInput for anything else).
std::optional<double> parse_scale(const std::string& text);

// The resolved configuration (every option with its value, defaults filled in), as written to
// OUT.config.json and into the stats.
nlohmann::json config_json(const DecodeRequest& request);

enum class OutputKind { kPng, kTiff, kNpy };

// .png -> kPng, .tif/.tiff -> kTiff, .npy -> kNpy (case-insensitive); anything else throws
// InvalidInput naming the path and the extensions accepted.
OutputKind output_kind(const std::filesystem::path& path);

const char* output_kind_name(OutputKind kind);

// .tif/.npy hold float32: an estimate beyond the float32 range (|x| > 3.4e38) would be written
// as Inf, so it is refused (InvalidInput naming the output) instead.
void check_output_range(const Image& estimate, OutputKind kind);

// The PNG values in [0, 1] (before write_png's clamp) and the factor used. `scale` empty means
// 1 / max; a non-positive maximum (an all-dark estimate) gives factor 0, all black.
struct ScaledImage {
    Image image;
    double factor = 0.0;
    double max_value = 0.0;  // max over channels after clipping negatives
};
ScaledImage scale_for_png(const Image& estimate, std::optional<double> scale);

// Writes `image` to `path` in the given kind (PNG with `bits` 8 or 16 from [0, 1] values;
// TIFF/npy float32 raw values). Not atomic by itself: callers stage it.
void write_output_image(const std::filesystem::path& path, const Image& image, OutputKind kind,
                        int bits);

// The period check as JSON (per-axis figures, skip reasons, tolerance, verdict).
nlohmann::json period_check_json(const PeriodCheck& check);

// One line per problem for stderr: a mismatch or a missing repeat, with measured and expected
// figures; empty when every checked axis matched (or nothing was checked).
std::string period_warning(const PeriodCheck& check);

// Why the check was skipped, axis by axis; empty when both axes were checked.
std::string period_skip_note(const PeriodCheck& check);

}  // namespace pinmask::cli
