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

bool is_iterative(DecodeMethod m) {
    return m == DecodeMethod::kTv || m == DecodeMethod::kTvqc || m == DecodeMethod::kRichardsonLucy;
}

}  // namespace pinmask
