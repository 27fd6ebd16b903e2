#include "io/camera_json.hpp"

#include <cstdint>
#include <fstream>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/input_file.hpp"
#include "io/json_strict.hpp"
#include "io/optics_json.hpp"

namespace pinmask::io {

using namespace json_strict;

namespace {

// A camera file is a few hundred bytes; anything past this is not one.
constexpr std::uintmax_t kMaxCameraFileBytes = 1 << 20;

}  // namespace

std::string camera_file_text(const Camera& camera) {
    validate(camera);
    nlohmann::ordered_json j;
    j["format"] = "pinmask-camera";
    j["version"] = kCameraFileVersion;
    j["optics"] = optics_to_json<nlohmann::ordered_json>(camera);
    return j.dump(2) + "\n";
}

Camera read_camera_file(const std::filesystem::path& path) {
    const std::string name = path.string();
    if (const auto problem = input_file_problem(path))
        throw InvalidInput(name + ": cannot read camera file (" + *problem + ")");
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw InvalidInput(name + ": cannot read camera file (" + ec.message() + ")");
    if (size > kMaxCameraFileBytes) {
        throw InvalidInput(name + ": " + std::to_string(size) +
                           " bytes is too large for a camera file (at most 1 MiB)");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput(name + ": cannot open camera file for reading");
    std::ostringstream buf;
    buf << in.rdbuf();
    try {
        const Json j = parse_strict(buf.str());
        ObjectReader r(j, "", {"format", "version", "optics"});
        r.reject_unknown();
        const std::string format = read_string(r.required("format"), "format");
        if (format != "pinmask-camera") {
            throw invalid_field("format", "'" + format + "'", "must be 'pinmask-camera'");
        }
        const int version = read_int(r.required("version"), "version");
        if (version != kCameraFileVersion) {
            throw invalid_field("version", std::to_string(version),
                                "must be " + std::to_string(kCameraFileVersion));
        }
        return optics_from_json(r.required("optics"));
    } catch (const Json::parse_error& e) {
        throw InvalidInput(name + ": invalid JSON (byte " + std::to_string(e.byte) +
                           "): " + json_error_words(e));
    } catch (const Json::exception& e) {
        throw InvalidInput(name + ": invalid JSON: " + json_error_words(e));
    } catch (const InvalidInput& e) {
        throw InvalidInput(name + ": " + e.what());
    }
}

void write_camera_file(const std::filesystem::path& path, const Camera& camera) {
    write_bytes_atomic(path, camera_file_text(camera));
}

}  // namespace pinmask::io
