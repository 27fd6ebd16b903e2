// Atomic file output: every file is written under a temporary sibling name and renamed into
// place, so a crash or an error never leaves a half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace pinmask {

// Calls write(tmp_path), then renames tmp_path to path. On any exception the temporary file is
// removed and the exception propagates; path is untouched.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes bytes (text or binary) atomically.
void write_bytes_atomic(const std::filesystem::path& path, std::string_view bytes);

// A group of files that appear together or not at all: stage() writes each to a temporary name,
// commit() renames them all; destroying an uncommitted group removes every temporary file.
class StagedFiles {
  public:
    StagedFiles() = default;
    StagedFiles(const StagedFiles&) = delete;
    StagedFiles& operator=(const StagedFiles&) = delete;
    ~StagedFiles();

    void stage(const std::filesystem::path& path,
               const std::function<void(const std::filesystem::path& tmp)>& write);
    void stage_bytes(const std::filesystem::path& path, std::string_view bytes);
    void commit();
    const std::vector<std::filesystem::path>& final_paths() const { return finals_; }

  private:
    std::vector<std::filesystem::path> temps_, finals_;
    bool committed_ = false;
};

}  // namespace pinmask
