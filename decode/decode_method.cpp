#include "decode/decode_method.hpp"

#include "core/error.hpp"

namespace pinmask {

const char* decode_method_name(DecodeMethod m) {
    switch (m) {
        case DecodeMethod::kWiener:
            return "wiener";
        case DecodeMethod::kTikhonov:
            return "tikhonov";
        case DecodeMethod::kTv:
            return "tv";
        case DecodeMethod::kTvqc:
            return "tvqc";
        case DecodeMethod::kRichardsonLucy:
            return "richardson-lucy";
    }
    throw InvalidInput("decode method: unknown enum value " + std::to_string(static_cast<int>(m)));
}

std::string decode_method_names() {
    std::string out;
    for (DecodeMethod m : kDecodeMethods)
        out += (out.empty() ? "" : " | ") + std::string(decode_method_name(m));
    return out;
}

DecodeMethod parse_decode_method(std::string_view name, std::string_view field) {
    for (DecodeMethod m : kDecodeMethods)
        if (name == decode_method_name(m)) return m;
    throw invalid_field(std::string(field), std::string(name),
                        "must be one of " + decode_method_names());
}

bool is_iterative(DecodeMethod m) {
    return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc || m == DecodeMethod::kRichardsonLucy;
}

bool decode_method_uses(DecodeMethod m, DecodeParameter p) {
    switch (p) {
        case DecodeParameter::kNsr:
            return m == DecodeMethod::kWiener;
        case DecodeParameter::kLambda:
            return m == DecodeMethod::kTikhonov || m == DecodeMethod::kTv;
        case DecodeParameter::kRegulariser:
            return m == DecodeMethod::kTikhonov;
        case DecodeParameter::kEps:
        case DecodeParameter::kNoiseSigma:
            return m == DecodeMethod::kTvqc;
        case DecodeParameter::kNonnegative:
            return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc;
        case DecodeParameter::kIterations:
        case DecodeParameter::kTolerance:
            return is_iterative(m);
    }
    return false;
}

}  // namespace pinmask
