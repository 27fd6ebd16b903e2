// The one check every reader of an outside file runs before opening it: the path must name a
// regular file (after symbolic links). A named pipe would block the run until a writer appears,
// a device such as /dev/zero never ends, a socket cannot be opened: each is refused by name,
// before any read. A regular file that passes is an input of the run from then on
// (core/files/output_set protect_input): every reader goes through here, so no output of the run,
// the checkpoints, snapshots, reports and sidecars included, can replace a file it read.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace pinmask {

// Why `path` cannot be read as an input file ("does not exist", "is a directory", "is a named
// pipe: ...", a NUL byte inside the name), or nullopt when it is a regular file (then protected
// as an input of this run).
std::optional<std::string> input_file_problem(const std::filesystem::path& path);

// What an existing path that is not a regular file or a directory is: "a named pipe", "a
// character device", "a block device", "a socket", or "not a regular file".
const char* special_file_kind(const std::filesystem::file_status& status);

}  // namespace pinmask
