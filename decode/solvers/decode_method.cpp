#include "decode/solvers/decode_method.hpp"

#include "core/errors/error.hpp"

namespace pinmask {

const char* decode_method_name(DecodeMethod m) {
    return name_of(kDecodeMethodNames, m, "decode method");
}

std::string decode_method_names() { return names_of(kDecodeMethodNames); }

DecodeMethod parse_decode_method(std::string_view name, std::string_view field) {
    return parse_name(kDecodeMethodNames, name, field);
}

std::optional<DecodeMethod> parse_decode_method_or_auto(std::string_view name,
                                                        std::string_view field) {
    if (name == "auto") return std::nullopt;
    for (const auto& [method, method_name] : kDecodeMethodNames)
        if (name == method_name) return method;
    throw invalid_field(std::string(field), std::string(name),
                        "must be one of auto | " + decode_method_names());
}

bool is_iterative(DecodeMethod m) {
    return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc || m == DecodeMethod::kRichardsonLucy;
}

}  // namespace pinmask
