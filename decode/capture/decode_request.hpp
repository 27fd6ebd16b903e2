// A decode as a user asks for it: the settings of the capture pipeline
// (decode/capture/capture_pipeline.hpp) with every method's parameters side by side, typed, before
// they are sorted into the options struct of the chosen method. Shared by the decode command and
// the Python module, which parse their own text and arguments into it; errors name the fields of
// this struct through field_ref (core/errors/field_names.hpp), which each face spells its own way.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "decode/capture/capture.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/decode_modes.hpp"

namespace pinmask {

// The background a request subtracts: none, the PSF's corner patch, a value in counts, or (auto,
// the default) a measured PSF's floor (decode/capture/capture_defaults.hpp).
struct DecodeBackground {
    BackgroundMode mode = BackgroundMode::kAuto;
    double value = 0.0;  // kValue only: counts off the capture
};

// Every setting of a decode, with its default. The method's parameters are all here, whatever
// the method; decode_options keeps the ones the method reads.
struct DecodeRequest {
    CropSpec crop{};  // kCenter: the period centred in the frame, when crop_auto is false
    DecodeMethod method = DecodeMethod::kWiener;  // when method_auto is false
    // "auto", the default: wiener or tv chosen from the model and the capture
    // (decode/capture/capture_defaults.hpp auto_method_is_tv). A face sets it false when the
    // user gives a method; resolve_implied_method sets it false when a given parameter is read
    // by only one of the two (method_implied_by then names that parameter's field).
    bool method_auto = true;
    std::string method_implied_by;
    ConvModel model = ConvModel::kCyclic;  // when model_auto is false
    // "auto", the default: the model, the crop and (tv, tvqc) non-negativity read from the capture
    // and the PSF (decode/capture/capture_defaults.hpp) in place of the values given here. A face
    // sets each false when the user gives a value.
    bool model_auto = true, crop_auto = true, nonnegative_auto = true;
    double nsr = 0.01;     // wiener, when nsr_auto is false
    double lambda = 1e-3;  // tikhonov (> 0), tv (>= 0), when lambda_auto is false
    // "auto", the default: the weight chosen from the capture (decode/solvers/auto_weight.hpp) in
    // place of the number above: wiener's nsr, tikhonov's and tv's lambda. A face sets them false
    // when the user gives a number (or, for wiener, a per-frequency NSR map).
    bool nsr_auto = true, lambda_auto = true;
    TikhonovRegulariser regulariser = TikhonovRegulariser::kIdentity;
    std::optional<double> eps, noise_sigma;  // tvqc: one of them
    bool nonnegative = false;                // tv, tvqc, when nonnegative_auto is false
    int iterations = 200;                    // tv, tvqc, richardson-lucy
    double tolerance = 1e-4;                 // tv, tvqc, richardson-lucy
    int downsample = 0;
    DecodeBackground background{};
    NormalizeMode normalize = NormalizeMode::kNone;
    int threads = 0;  // 0: all cores
    Precision precision = Precision::kAuto;
};

// The request's fields that set a parameter of one method's struct in DecodeOptions
// (decode/capture/decoder.hpp).
enum class MethodParameter {
    kNsr,          // wiener.nsr
    kLambda,       // tikhonov.lambda, tv.lambda
    kRegulariser,  // tikhonov.regulariser
    kEps,          // tvqc.eps
    kNoiseSigma,   // tvqc.noise_sigma
    kNonnegative,  // tv.nonnegative, tvqc.nonnegative
    kIterations,   // iterative.max_iterations (tv, tvqc, richardson-lucy)
    kTolerance,    // iterative.tolerance (tv, tvqc, richardson-lucy)
};
inline constexpr MethodParameter kMethodParameters[] = {
    MethodParameter::kNsr,        MethodParameter::kLambda,     MethodParameter::kRegulariser,
    MethodParameter::kEps,        MethodParameter::kNoiseSigma, MethodParameter::kNonnegative,
    MethodParameter::kIterations, MethodParameter::kTolerance};
// The DecodeRequest field of a parameter: "nsr", "lambda", "regulariser", "eps", "noise_sigma",
// "nonnegative", "iterations", "tolerance" (for field_ref; the faces spell it).
const char* method_parameter_field(MethodParameter parameter);

// Writes the request's value for `parameter` into the options of d.method that hold that
// parameter; false when that method has no such parameter (its value would be dropped). The one
// place that says which parameter goes where: decode_options and the refusals below both use it.
bool write_method_parameter(DecodeOptions& d, MethodParameter parameter,
                            const DecodeRequest& request);

// A parameter the user gave (the CLI's flags counted, Python's arguments not None), with its
// value as the user wrote it (for the message).
struct GivenParameter {
    MethodParameter parameter;
    std::string value;
};
// The methods method auto chooses between: wiener and tv.
inline constexpr DecodeMethod kAutoMethods[] = {DecodeMethod::kWiener, DecodeMethod::kTv};

// Method auto with parameters given: no parameter is read by both wiener and tv, so a given one
// implies its method (nsr, or an NSR map when `nsr_map_given`: wiener; lambda, nonnegative,
// iterations, tolerance: tv), which is then the method (method_auto false, method_implied_by
// the first such field). InvalidInput naming the parameter when it is read by neither (give the
// method that reads it) or when two given parameters imply different methods. Nothing happens
// when the method was given.
void resolve_implied_method(DecodeRequest& request, const std::vector<GivenParameter>& given,
                            bool nsr_map_given);

// InvalidInput naming the first given parameter that the request's method does not read and
// the methods that do; then the refusal of lambda <= 0 for tikhonov. After
// resolve_implied_method (method auto with a parameter given is then resolved or refused).
void refuse_unused_parameters(const DecodeRequest& request,
                              const std::vector<GivenParameter>& given);

// The DecodeOptions of a request: method, model, and every parameter the chosen method reads
// (write_method_parameter); with method auto, every parameter wiener or tv reads (the method is
// left wiener until the pipeline chooses). Whether the iterations are recorded
// (iterative.record_history) is left at its default: each face sets it by what it shows.
DecodeOptions decode_options(const DecodeRequest& request);
// The pipeline options of a request (crop, background, downsample, normalize, decode, the
// automatic settings, precision, threads).
CaptureDecodeOptions capture_decode_options(const DecodeRequest& request);

}  // namespace pinmask
