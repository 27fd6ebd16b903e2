// The flags of `pinmask decode` (with their help texts) and the refusal of flags the chosen
// method does not read: a value given for a parameter the method ignores is an error (exit 2
// naming the flag), never silently dropped: cli/decode_output.hpp write_method_flag says which
// method's options struct each flag writes to.
#pragma once

#include <CLI/CLI.hpp>
#include <utility>
#include <vector>

#include "cli/decode_output.hpp"
#include "decode/decode_method.hpp"

namespace pinmask::cli {

// The method-specific flags as parsed, each with the parameter it sets.
struct DecodeFlags {
    std::vector<std::pair<CLI::Option*, MethodFlag>> method_flags;
};

// Adds every decode flag to `cmd`, writing into `request`.
DecodeFlags add_decode_flags(CLI::App& cmd, DecodeRequest& request);

// After parsing: InvalidInput naming the first flag given that --method does not read, and
// the refusals of values that are legal for the type but meaningless (--lambda 0 for tikhonov).
void refuse_unused_flags(const DecodeRequest& request, const DecodeFlags& flags);

extern const char* const kDecodeFooter;

}  // namespace pinmask::cli
