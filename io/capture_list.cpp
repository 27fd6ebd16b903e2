#include "io/capture_list.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/input_file.hpp"
#include "core/files/path_text.hpp"
#include "core/image/raw_io.hpp"

namespace pinmask::io {
namespace {

namespace fs = std::filesystem;

// A list names one capture a line: 64 MiB holds about a million paths.
constexpr std::uintmax_t kMaxListBytes = 64ull << 20;

bool capture_extension(const fs::path& p) {
    std::string e = p.extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e == ".tif" || e == ".tiff" || e == ".png" || e == ".npy" || e == ".jpg" ||
           e == ".jpeg" || is_raw_extension(p);
}

std::string trimmed(const std::string& line) {
    std::size_t start = 0, end = line.size();
    while (start < end && std::isspace(static_cast<unsigned char>(line[start]))) ++start;
    while (end > start && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
    return line.substr(start, end - start);
}

// The batch summary (JSON, UTF-8 only) records every capture's name: a name with other bytes
// would fail when the summary is written, after every decode.
const std::vector<std::string>& utf8_names(const std::vector<std::string>& paths,
                                           const std::string& list_or_dir) {
    for (const std::string& p : paths)
        if (invalid_utf8_at(p) != std::string::npos)
            throw invalid_field(field_ref("batch"), printable_text(p),
                                "in " + printable_text(list_or_dir) +
                                    ": the name is not UTF-8 text, and the batch's JSON files "
                                    "hold UTF-8 only: rename the file");
    return paths;
}

}  // namespace

std::vector<std::string> capture_list(const std::string& list_or_dir) {
    std::error_code ec;
    if (list_or_dir.empty() || !fs::exists(list_or_dir, ec))
        throw invalid_field(field_ref("batch"), list_or_dir, "no such directory or list file");
    std::vector<std::string> paths;
    if (fs::is_directory(list_or_dir, ec)) {
        for (const auto& e : fs::directory_iterator(list_or_dir))
            if (e.is_regular_file() && capture_extension(e.path()))
                paths.push_back(e.path().string());
        std::sort(paths.begin(), paths.end());
        if (paths.empty())
            throw invalid_field(field_ref("batch"), list_or_dir,
                                "the directory holds no capture (.tif, .tiff, .png, .npy, .jpg, "
                                ".jpeg or a camera RAW file such as .dng)");
        return utf8_names(paths, list_or_dir);
    }
    if (const auto problem = input_file_problem(list_or_dir))
        throw invalid_field(field_ref("batch"), list_or_dir, *problem);
    if (fs::file_size(list_or_dir, ec) > kMaxListBytes)
        throw invalid_field(field_ref("batch"), list_or_dir,
                            "a list file of more than 64 MiB (one capture path a line)");
    std::ifstream in(list_or_dir);
    if (!in) throw invalid_field(field_ref("batch"), list_or_dir, "cannot be read");
    for (std::string raw; std::getline(in, raw);) {
        const std::string line = trimmed(raw);
        if (line.empty() || line[0] == '#') continue;
        if (const auto at = line.find('\0'); at != std::string::npos)  // read up to it
            throw invalid_field(
                field_ref("batch"), line.substr(0, at),
                "listed in " + list_or_dir + ": the line holds a NUL byte, which no file name can");
        if (!fs::is_regular_file(line, ec))
            throw invalid_field(field_ref("batch"), line,
                                "listed in " + list_or_dir + ": no such file");
        paths.push_back(line);
    }
    if (paths.empty())
        throw invalid_field(field_ref("batch"), list_or_dir, "the list names no capture");
    return utf8_names(paths, list_or_dir);
}

}  // namespace pinmask::io
