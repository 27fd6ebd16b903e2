// Fuzzes the GDSII reader (export/formats/gds_reader read_gds) and the design-rule check on what it
// returns (fuzz_fabrication.hpp).
#include <cstddef>
#include <cstdint>

#include "export/formats/gds_reader.hpp"
#include "fuzz/fuzz_fabrication.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return pinmask::fuzz::fuzz_fabrication_reader(pinmask::read_gds, data, size);
}
