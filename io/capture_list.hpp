// The captures of `decode --batch LIST_OR_DIR`: a directory (its .tif/.tiff/.png/.npy/
// .jpg/.jpeg files and camera RAW files by core/image/raw_io's extensions, sorted by name) or a
// text file of paths, one a line (blank lines and lines starting with '#' skipped; surrounding
// spaces trimmed; relative paths are relative to the current directory).
#pragma once

#include <string>
#include <vector>

namespace pinmask::io {

// The capture paths, in order. InvalidInput naming `batch` (the list or directory) for a missing
// path, an empty directory or list, or a listed file that does not exist.
std::vector<std::string> capture_list(const std::string& list_or_dir);

}  // namespace pinmask::io
