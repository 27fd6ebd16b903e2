// Fuzzes the camera file reader (io/camera_json, `--camera FILE` of every command with camera
// flags) through a scratch file: any bytes give a Camera or InvalidInput, never another exception.
// An accepted camera obeys the camera's own rules (design/optics/camera validate) and round-trips.
#include <cstddef>
#include <cstdint>

#include "core/errors/error.hpp"
#include "design/optics/camera.hpp"
#include "fuzz/fuzz_support.hpp"
#include "io/camera_json.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const auto& path = fuzz::write_scratch(data, size, ".camera.json");
    Camera c;
    try {
        c = io::read_camera_file(path);
    } catch (const InvalidInput&) {
        return 0;
    }
    try {
        validate(c);
    } catch (const InvalidInput&) {
        fuzz::invariant_failed("the reader accepted a camera that validate() refuses");
    }
    if (io::camera_file_text(c).empty())
        fuzz::invariant_failed("an accepted camera writes nothing");
    return 0;
}
