// Fuzzes the export sidecar reader (io/export_sidecar, read by `pinmask check FILE` when
// NAME.export.json sits beside FILE) through a scratch file: any bytes give an ExportSidecar or
// InvalidInput, never another exception. An accepted sidecar writes back to text.
#include <cstddef>
#include <cstdint>

#include "core/errors/error.hpp"
#include "fuzz/fuzz_support.hpp"
#include "io/export_sidecar.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const auto& path = fuzz::write_scratch(data, size, ".export.json");
    io::ExportSidecar s;
    try {
        s = io::read_export_sidecar(path);
    } catch (const InvalidInput&) {
        return 0;
    }
    if (!(s.grid_nm >= 1)) fuzz::invariant_failed("a grid below 1 nm accepted");
    if (io::export_sidecar_text(s).empty())
        fuzz::invariant_failed("an accepted sidecar writes nothing");
    return 0;
}
