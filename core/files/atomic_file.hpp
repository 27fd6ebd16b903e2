// Atomic file output: every file is written under a temporary sibling name and renamed into
// place, so a crash or an error never leaves a half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace pinmask {

// Calls write(tmp_path), then renames tmp_path to path. On any exception the temporary file is
// removed and the exception propagates; path is untouched.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes bytes (text or binary) atomically.
void write_bytes_atomic(const std::filesystem::path& path, std::string_view bytes);

// Unlinks every temporary file that write_file_atomic or a StagedFiles group has created and not
// yet renamed or removed. Async-signal-safe (atomic loads and unlink only): a face's handler of a
// fatal signal calls it before the process dies, so an interrupted run leaves no *.tmp-* file.
// A temporary being renamed at that moment may already carry its final name (that file is whole).
void remove_pending_temporaries() noexcept;

// A group of files that appear together or not at all: stage() writes each to a temporary name
// in the target directory, commit() renames them all; destroying an uncommitted group removes
// every temporary file. stage() refuses (InvalidInput, before writing) a final name that is an
// existing directory, an input this process read (core/files/output_set protect_input) or a name
// already staged in the group. commit() first moves any existing file under a final name aside;
// if a rename fails it removes the files already renamed, puts the old ones back and throws
// RuntimeFailure saying so: the folder is as it was before the run.
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
    // Test hook: make the rename of the i-th staged file (0-based) fail in the next commit of
    // any group (-1: none).
    static void fail_rename_for_test(int index);
    const std::vector<std::filesystem::path>& final_paths() const { return finals_; }

  private:
    std::vector<std::filesystem::path> temps_, finals_;
    std::vector<void*> slots_;  // this group's entries of the pending-temporaries list
    std::unordered_set<std::string> final_keys_;  // core/files/output_set same_file_keys of finals_
    bool committed_ = false;
};

}  // namespace pinmask
