// The name tables of decode's modes (one per enum, the only place each spelling is written):
// convolution model, Tikhonov regulariser, background, normalisation and precision. Used by
// the CLI (flag values, the stats and config JSON) and Python. The decode methods' table is
// decode/solvers/decode_method.hpp. Unknown names are InvalidInput naming the field, the value and
// the names accepted.
#pragma once

#include <string>
#include <string_view>

#include "core/errors/name_table.hpp"
#include "decode/capture/decoder.hpp"

namespace pinmask {

// kAuto: read from the PSF (decode/capture/capture_defaults.hpp).
enum class BackgroundMode { kNone, kCorner, kValue, kAuto };
enum class NormalizeMode { kNone, kL2 };
enum class Precision { kAuto, kSingle, kDouble };

inline constexpr NameTable<ConvModel, 2> kConvModelNames{
    {{ConvModel::kCyclic, "cyclic"}, {ConvModel::kLinear, "linear"}}};
inline constexpr NameTable<TikhonovRegulariser, 2> kRegulariserNames{
    {{TikhonovRegulariser::kIdentity, "identity"}, {TikhonovRegulariser::kGradient, "gradient"}}};
// "value": a number of counts (the CLI's --background VALUE); its name is the mode in the stats.
inline constexpr NameTable<BackgroundMode, 4> kBackgroundModeNames{
    {{BackgroundMode::kNone, "none"},
     {BackgroundMode::kCorner, "corner"},
     {BackgroundMode::kValue, "value"},
     {BackgroundMode::kAuto, "auto"}}};
inline constexpr NameTable<NormalizeMode, 2> kNormalizeModeNames{
    {{NormalizeMode::kNone, "none"}, {NormalizeMode::kL2, "l2"}}};
inline constexpr NameTable<Precision, 3> kPrecisionNames{
    {{Precision::kAuto, "auto"}, {Precision::kSingle, "single"}, {Precision::kDouble, "double"}}};

inline const char* conv_model_name(ConvModel m) { return name_of(kConvModelNames, m, "model"); }
inline ConvModel parse_conv_model(std::string_view s, std::string_view field = "model") {
    return parse_name(kConvModelNames, s, field);
}
inline const char* regulariser_name(TikhonovRegulariser r) {
    return name_of(kRegulariserNames, r, "regulariser");
}
inline TikhonovRegulariser parse_regulariser(std::string_view s,
                                             std::string_view field = "regulariser") {
    return parse_name(kRegulariserNames, s, field);
}
inline const char* background_mode_name(BackgroundMode m) {
    return name_of(kBackgroundModeNames, m, "background");
}
inline const char* normalize_mode_name(NormalizeMode m) {
    return name_of(kNormalizeModeNames, m, "normalize");
}
inline NormalizeMode parse_normalize_mode(std::string_view s,
                                          std::string_view field = "normalize") {
    return parse_name(kNormalizeModeNames, s, field);
}
inline const char* precision_name(Precision p) { return name_of(kPrecisionNames, p, "precision"); }
inline Precision parse_precision(std::string_view s, std::string_view field = "precision") {
    return parse_name(kPrecisionNames, s, field);
}

}  // namespace pinmask
