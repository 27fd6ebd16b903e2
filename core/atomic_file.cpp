#include "core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>

#include "core/error.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

fs::path temp_sibling(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = path;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return tmp;
}

void write_bytes(const fs::path& p, std::string_view bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    if (!out) throw RuntimeFailure("cannot open " + p.string() + " for writing");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw RuntimeFailure("failed writing " + p.string());
}

}  // namespace

void write_file_atomic(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path tmp = temp_sibling(path);
    try {
        write(tmp);
        fs::rename(tmp, path);
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
}

void write_bytes_atomic(const fs::path& path, std::string_view bytes) {
    write_file_atomic(path, [&](const fs::path& tmp) { write_bytes(tmp, bytes); });
}

StagedFiles::~StagedFiles() {
    if (committed_) return;
    for (const auto& t : temps_) {
        std::error_code ec;
        fs::remove(t, ec);
    }
}

void StagedFiles::stage(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path tmp = temp_sibling(path);
    temps_.push_back(tmp);
    finals_.push_back(path);
    write(tmp);
}

void StagedFiles::stage_bytes(const fs::path& path, std::string_view bytes) {
    stage(path, [&](const fs::path& tmp) { write_bytes(tmp, bytes); });
}

void StagedFiles::commit() {
    for (std::size_t i = 0; i < temps_.size(); ++i) fs::rename(temps_[i], finals_[i]);
    committed_ = true;
}

}  // namespace pinmask
