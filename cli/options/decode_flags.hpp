// The flags of `pinmask decode` (with their help texts), the command's settings they fill, and
// the refusal of flags the chosen method does not read: a value given for a parameter the
// method ignores is an error (exit 2 naming the flag), never silently dropped
// (decode/capture/decode_request.hpp write_method_parameter says which method's options struct each
// parameter writes to).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "decode/capture/decode_request.hpp"
#include "decode/solvers/decode_method.hpp"
#include "decode/solvers/decode_modes.hpp"

namespace pinmask::cli {

// Everything `pinmask decode` is told: the input files, the library's settings and the
// command's own output settings.
struct DecodeCommand {
    std::string capture, mask, psf, dark;
    // --object-distance: refocus the mask's PSF to an object at this distance.
    std::optional<std::string> object_distance;
    // --nsr-map: a file of per-frequency NSRs (wiener only; replaces nsr), read into
    // DecodeOptions::wiener.nsr_per_frequency (cli/options/decode_inputs load_nsr_map).
    std::string nsr_map;
    // The library's settings: the numbers are parsed into it directly; the flags given as text
    // (below) are parsed into it by resolve_method and resolve_request.
    DecodeRequest request;
    // The text flags as given; OUT.config.json and the stats repeat them as given. Their
    // defaults are the request's: its names, or "auto" where it reads the value from the data.
    std::string crop = "auto";  // auto | center | centre | none | X,Y
    std::string method =        // auto | decode_method.hpp names
        request.method_auto ? "auto" : decode_method_name(request.method);
    std::string model = "auto";                                       // auto | cyclic | linear
    std::string regulariser = regulariser_name(request.regulariser);  // identity | gradient
    std::string background = background_mode_name(request.background.mode);  // or none, VALUE
    bool no_nonneg = false;  // --no-nonneg: tv, tvqc without x >= 0 (not auto)
    std::string normalize = normalize_mode_name(request.normalize);  // none | l2
    std::string precision = precision_name(request.precision);       // auto | single | double
    std::string nsr = "auto";                                        // a number | auto
    std::string lambda = "auto";                                     // a number | auto
    std::string bayer = "sum2x2";  // camera RAW demosaic: sum2x2 | green | r | b
    bool bayer_given = false;      // --bayer given: also applied to a mosaic in an image file
    // The command's output settings.
    std::string output;
    int bits = 8;
    std::string scale = "max";  // max | VALUE
    std::string stats;
    bool json = false;
    bool explain = false;
    bool quiet = false;  // no progress lines
};

// The method-specific flags as parsed, each with the parameter it sets.
struct DecodeFlags {
    std::vector<std::pair<CLI::Option*, MethodParameter>> method_flags;
};

// Adds every decode flag to `cmd`, writing into `command`.
DecodeFlags add_decode_flags(CLI::App& cmd, DecodeCommand& command);

// After parsing: parses --method into command.request (auto: a flag only wiener or only tv
// reads implies that method, decode/capture/decode_request.hpp resolve_implied_method), then
// InvalidInput naming the first flag given that the method does not read, and the refusals of
// values that are legal for the type but meaningless (--lambda 0 for tikhonov).
void resolve_method(DecodeCommand& command, const DecodeFlags& flags);

// Flags this run would ignore are refused, as the method's parameters are (resolve_method): the
// batch's flags (--batch-format, --batch-stats) without --batch (`batch`), and PNG's --bits and
// --scale for .tif/.tiff and .npy output (`batch_format` under --batch, else -o's extension).
void refuse_ignored_output_flags(const CLI::App& cmd, const DecodeCommand& command, bool batch,
                                 const std::string& batch_format);

// Parses the remaining text flags (--crop, --background, --model, --regulariser, --normalize,
// --precision; "auto" where the setting has one) into command.request; InvalidInput naming the
// flag otherwise.
void resolve_request(DecodeCommand& command);

// --crop: center (or centre) | none | X,Y (integer top-left column, row). InvalidInput otherwise
// ("auto" is resolve_request's).
CropSpec parse_crop(const std::string& text);

// --background: auto | none | corner | a number of counts (mode "value").
DecodeBackground parse_background(const std::string& text);

// --scale: "max" -> empty; a factor > 0 otherwise (InvalidInput for anything else).
std::optional<double> parse_scale(const std::string& text);

extern const char* const kDecodeFooter;

}  // namespace pinmask::cli
