#include "core/files/input_file.hpp"

#include <system_error>

#include "core/files/output_set.hpp"

namespace pinmask {

std::optional<std::string> input_file_problem(const std::filesystem::path& path) {
    namespace fs = std::filesystem;
    // The system reads a name up to its first NUL byte: a name with one (an escaped "\u0000"
    // in a JSON file) would open the file named by its prefix.
    if (path.native().find('\0') != std::string::npos)
        return std::string("the name holds a NUL byte (\\u0000), which no file name can");
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) return std::string("file does not exist");
    if (fs::is_regular_file(st)) {
        protect_input(path);  // about to be read: no output of this run may replace it
        return std::nullopt;
    }
    if (fs::is_directory(st)) return std::string("is a directory");
    return std::string("is ") + special_file_kind(st) +
           ": pinmask reads only regular files (save it to a file)";
}

const char* special_file_kind(const std::filesystem::file_status& st) {
    namespace fs = std::filesystem;
    return fs::is_fifo(st)             ? "a named pipe"
           : fs::is_character_file(st) ? "a character device"
           : fs::is_block_file(st)     ? "a block device"
           : fs::is_socket(st)         ? "a socket"
                                       : "not a regular file";
}

}  // namespace pinmask
