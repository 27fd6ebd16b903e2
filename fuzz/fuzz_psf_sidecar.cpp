// Fuzzes the PSF sidecar reader (io/psf_files: parse_strict then psf_sidecar_from_json), the
// JSON that comes with a PSF file (decode --psf). Syntax errors are
// nlohmann exceptions from parse_strict (read_psf_file maps them to InvalidInput); the sidecar
// reader itself may throw only InvalidInput. An accepted sidecar round-trips through
// psf_sidecar_to_json unchanged.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors/error.hpp"
#include "fuzz/fuzz_support.hpp"
#include "io/json_strict.hpp"
#include "io/psf_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const std::string text(fuzz::as_text(data, size));
    nlohmann::json j;
    try {
        j = io::json_strict::parse_strict(text);
    } catch (const InvalidInput&) {
        return 0;
    } catch (const nlohmann::json::exception&) {
        return 0;
    }
    io::PsfSidecar s;
    try {
        s = io::psf_sidecar_from_json(j, "fuzz.json");
    } catch (const InvalidInput&) {
        return 0;
    }
    const nlohmann::json back = nlohmann::json::parse(io::psf_sidecar_to_json(s).dump());
    const io::PsfSidecar again = io::psf_sidecar_from_json(back, "round trip");
    if (io::psf_sidecar_to_json(again) != io::psf_sidecar_to_json(s)) {
        fuzz::invariant_failed("sidecar round trip");
    }
    return 0;
}
