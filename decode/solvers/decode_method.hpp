// The one name table of the decode methods, used by the CLI (flag values), the stats, the
// benchmarks and Python. Which parameters a method reads is the shape of DecodeOptions (one
// struct per method, decode/capture/decoder.hpp), not a table.
//
// One spelling per method: wiener, tikhonov, tv, tvqc, richardson-lucy. An unknown name is an
// error (InvalidInput naming the field, the value and the names accepted), never a fall-through.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "core/errors/name_table.hpp"
#include "decode/capture/decoder.hpp"

namespace pinmask {

inline constexpr NameTable<DecodeMethod, 5> kDecodeMethodNames{
    {{DecodeMethod::kWiener, "wiener"},
     {DecodeMethod::kTikhonov, "tikhonov"},
     {DecodeMethod::kTv, "tv"},
     {DecodeMethod::kTvqc, "tvqc"},
     {DecodeMethod::kRichardsonLucy, "richardson-lucy"}}};
inline constexpr std::array<DecodeMethod, 5> kDecodeMethods = {
    DecodeMethod::kWiener, DecodeMethod::kTikhonov, DecodeMethod::kTv, DecodeMethod::kTvqc,
    DecodeMethod::kRichardsonLucy};

// "wiener", "tikhonov", "tv", "tvqc", "richardson-lucy".
const char* decode_method_name(DecodeMethod method);
// The names joined by " | " (for help texts and messages).
std::string decode_method_names();
// Parses a name; throws InvalidInput naming `field` for anything else.
DecodeMethod parse_decode_method(std::string_view name, std::string_view field = "method");

// "auto" (empty: the method is chosen from the capture, decode/capture/capture_defaults.hpp) or
// a method's name; InvalidInput naming `field` and the names accepted, auto first, otherwise.
std::optional<DecodeMethod> parse_decode_method_or_auto(std::string_view name,
                                                        std::string_view field = "method");

bool is_iterative(DecodeMethod method);

}  // namespace pinmask
