// Fuzzes the Gerber reader (export/formats/gerber_reader read_gerber) and the design-rule check on
// what it returns (fuzz_fabrication.hpp).
#include <cstddef>
#include <cstdint>

#include "export/formats/gerber_reader.hpp"
#include "fuzz/fuzz_fabrication.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return pinmask::fuzz::fuzz_fabrication_reader(pinmask::read_gerber, data, size);
}
