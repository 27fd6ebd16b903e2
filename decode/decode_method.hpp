// The one name table of the decode methods and of the parameters each method reads, used by the
// CLI (flag values, refusals of flags a method ignores), the stats, the benchmarks and Python.
//
// One spelling per method: wiener, tikhonov, tv, tvqc, richardson-lucy. An unknown name is an
// error (InvalidInput naming the field, the value and the names accepted), never a fall-through.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "decode/decoder.hpp"

namespace pinmask {

inline constexpr std::array<DecodeMethod, 5> kDecodeMethods = {
    DecodeMethod::kWiener, DecodeMethod::kTikhonov, DecodeMethod::kTv, DecodeMethod::kTvqc,
    DecodeMethod::kRichardsonLucy};

// "wiener", "tikhonov", "tv", "tvqc", "richardson-lucy".
const char* decode_method_name(DecodeMethod method);
// The names joined by " | " (for help texts and messages).
std::string decode_method_names();
// Parses a name; throws InvalidInput naming `field` for anything else.
DecodeMethod parse_decode_method(std::string_view name, std::string_view field = "method");

// The parameters of DecodeOptions beyond method and model; each method reads some of them.
enum class DecodeParameter {
    kNsr,          // wiener
    kLambda,       // tikhonov, tv
    kRegulariser,  // tikhonov
    kEps,          // tvqc
    kNoiseSigma,   // tvqc
    kNonnegative,  // tv, tvqc
    kIterations,   // tv, tvqc, richardson-lucy (max_iterations)
    kTolerance,    // tv, tvqc, richardson-lucy
};

// True when `method` reads `parameter`: a value given for a parameter the method does not read
// would be silently dropped, so callers refuse it (the CLI exits 2 naming the flag).
bool decode_method_uses(DecodeMethod method, DecodeParameter parameter);
bool is_iterative(DecodeMethod method);

}  // namespace pinmask
