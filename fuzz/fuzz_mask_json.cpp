// Fuzzes the mask-file reader (io/mask_json read_mask_file: strict JSON with the streamed
// pinhole array, then mask_from_json's validation). An accepted file must also round-trip:
// mask_file_text of the result is accepted again and reproduces itself byte for byte.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "fuzz/fuzz_support.hpp"
#include "io/mask_json.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const auto& path = fuzz::write_scratch(data, size, ".mask.json");
    Mask mask;
    try {
        mask = io::read_mask_file(path);
    } catch (const InvalidInput&) {
        return 0;
    }
    const std::string text = io::mask_file_text(mask);
    const auto& again_path = fuzz::scratch_path(".again.mask.json");
    write_bytes_atomic(again_path, text);
    const Mask again = io::read_mask_file(again_path);
    if (geometry_hash(again) != geometry_hash(mask)) fuzz::invariant_failed("geometry hash");
    if (io::mask_file_text(again) != text) fuzz::invariant_failed("mask file text round trip");
    return 0;
}
