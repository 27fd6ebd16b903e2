// A decode as a user asks for it: every setting of `pinmask decode` as given (text where the
// command line takes text), and the options of the capture pipeline (decode/capture_pipeline.hpp)
// and of the decoder it maps to. Shared by the decode command and the Python module; errors
// name the command-line flag.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "decode/capture.hpp"
#include "decode/capture_pipeline.hpp"
#include "decode/decode_modes.hpp"
#include "decode/decoder.hpp"

namespace pinmask {

// Every flag of `pinmask decode`, with its default (see --help for meanings and units).
struct DecodeRequest {
    std::string capture, mask, psf, dark;
    // --object-distance: refocus the mask's PSF to an object at this distance.
    std::optional<std::string> object_distance;
    std::string crop = "center";    // center | none | X,Y
    std::string method = "wiener";  // decode/decode_method.hpp names
    std::string model = "cyclic";
    double nsr = 0.01;
    // --nsr-map: a file of per-frequency NSRs (wiener only; replaces nsr). The CLI reads it into
    // DecodeOptions::wiener.nsr_per_frequency (cli/decode_inputs load_nsr_map).
    std::string nsr_map;
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

// --background: none | corner | a number of counts (mode "value").
struct DecodeBackground {
    BackgroundMode mode = BackgroundMode::kNone;
    double value = 0.0;
};
DecodeBackground parse_background(const std::string& text);

// --scale: "max" -> empty; a factor > 0 otherwise (InvalidInput for anything else).
std::optional<double> parse_scale(const std::string& text);

}  // namespace pinmask
