// Shared fixtures of the image I/O tests: a scratch directory, byte helpers, seeded images and
// the message of an InvalidInput that read_image must throw.
#pragma once

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <random>
#include <string>
#include <string_view>

#include "core/errors/error.hpp"
#include "core/image/image.hpp"
#include "core/image/image_io.hpp"

namespace pinmask::test {

// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class ScratchDir {
  public:
    explicit ScratchDir(const std::string& tag)
        : dir_(std::filesystem::temp_directory_path() /
               ("pinmask-" + tag + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    std::filesystem::path operator/(const std::string& name) const { return dir_ / name; }
    const std::filesystem::path& path() const { return dir_; }

  private:
    std::filesystem::path dir_;
};

inline std::string read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::filesystem::path& p, std::string_view bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Uniform values in [lo, hi) from a seeded generator.
inline Image random_image(int rows, int cols, int channels, double lo, double hi,
                          std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(lo, hi);
    Image im(rows, cols, channels);
    for (Plane& p : im.channels)
        for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    return im;
}

inline bool contains(const std::string& s, const std::string& sub) {
    return s.find(sub) != std::string::npos;
}

// The message of the InvalidInput read_image(path) throws; records a failure (and returns "")
// when it returns normally or throws anything else.
inline std::string read_error(const std::filesystem::path& path) {
    try {
        (void)read_image(path);
        FAIL_CHECK("read_image accepted " << path);
    } catch (const InvalidInput& e) {
        return e.what();
    } catch (const std::exception& e) {
        FAIL_CHECK("read_image threw a non-InvalidInput error: " << e.what());
    }
    return "";
}

// Writes `bytes` to dir/name, checks read_image refuses it with a message naming the file and
// containing every `needles` entry.
inline void expect_refused(const ScratchDir& dir, const std::string& name, const std::string& bytes,
                           std::initializer_list<const char*> needles) {
    const std::filesystem::path p = dir / name;
    write_bytes(p, bytes);
    const std::string msg = read_error(p);
    INFO(name << ": " << msg);
    CHECK(contains(msg, name));
    for (const char* n : needles) CHECK(contains(msg, n));
}

// An npy file of format version major.0 from a hand-written header dict (padded to 64 like
// numpy) and raw little-endian data.
inline std::string npy_bytes(int major, const std::string& dict, const std::string& data) {
    std::string h = dict;
    const std::size_t pre = major == 1 ? 10 : 12;
    h.append((64 - (pre + h.size() + 1) % 64) % 64, ' ');
    h += '\n';
    std::string out = "\x93NUMPY";
    out += char(major);
    out += '\0';
    for (std::size_t i = 0; i < pre - 8; ++i) out += char((h.size() >> (8 * i)) & 0xff);
    return out + h + data;
}

}  // namespace pinmask::test
