#include "core/files/atomic_file.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

fs::path temp_sibling(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path tmp = path;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return tmp;
}

// The temporaries that exist right now, readable from a signal handler: a list of slots that
// only grows (a slot is allocated outside any handler and reused once free), each holding a
// NUL-terminated path and a state. The handler reads only slots whose state is kLive.
struct TempSlot {
    static constexpr int kFree = 0, kWriting = 1, kLive = 2;
    std::atomic<int> state{kFree};
    std::string path;  // written only while kWriting; c_str() stable while kLive
    TempSlot* next = nullptr;
};
std::atomic<TempSlot*> g_slots{nullptr};
// Slots released and not yet reused (a hint, briefly off by one while a release and a claim
// race): with none free the list is not walked. A batch stages every output before committing
// any, so all slots are live while it stages; walking them for each new temporary made staging
// N files cost N^2 / 2 slot visits (10,000 captures: 34 % of the run).
std::atomic<long> g_free{0};

TempSlot* register_temp(const fs::path& tmp) {
    TempSlot* slot = nullptr;
    if (g_free.load() > 0) {
        for (TempSlot* s = g_slots.load(); s && !slot; s = s->next) {
            int expected = TempSlot::kFree;
            if (s->state.compare_exchange_strong(expected, TempSlot::kWriting)) slot = s;
        }
        if (slot) g_free.fetch_sub(1);
    }
    if (!slot) {
        slot = new TempSlot;  // never freed: the handler may be walking the list
        slot->state.store(TempSlot::kWriting);
        slot->next = g_slots.load();
        while (!g_slots.compare_exchange_weak(slot->next, slot)) {
        }
    }
    slot->path = tmp.string();
    slot->state.store(TempSlot::kLive);
    return slot;
}

void release_temp(TempSlot* slot) {
    if (!slot) return;
    slot->state.store(TempSlot::kFree);
    g_free.fetch_add(1);
}

// Registers a temporary for its lifetime (write_file_atomic's).
class TempGuard {
  public:
    explicit TempGuard(const fs::path& tmp) : slot_(register_temp(tmp)) {}
    TempGuard(const TempGuard&) = delete;
    TempGuard& operator=(const TempGuard&) = delete;
    ~TempGuard() { release_temp(slot_); }

  private:
    TempSlot* slot_;
};

// Plain POSIX writes, so a failure names the system's reason (no space left on device, file
// too large, disk quota exceeded).
void write_bytes(const fs::path& p, std::string_view bytes) {
    const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw RuntimeFailure("cannot open " + p.string() + ": " + std::strerror(errno));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = n < 0 ? errno : EIO;
            ::close(fd);
            throw RuntimeFailure("failed writing " + p.string() + ": " + std::strerror(err));
        }
        done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0)
        throw RuntimeFailure("failed writing " + p.string() + ": " + std::strerror(errno));
}

// Why a temporary is incomplete, or "": it reached the process's file-size limit (`ulimit -f`;
// with SIGXFSZ ignored, the write past it failed with EFBIG, which a writer library may ignore
// or report without the reason), whatever its writer said; or, when its writer failed, its file
// system has no block left (ENOSPC, the reason the writer's message may lack). A file exactly at
// the limit counts as cut: it cannot be told from one.
std::string cut_reason(const fs::path& tmp, bool writer_failed) {
    struct rlimit lim {};
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(tmp, ec);
    if (!ec && ::getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY &&
        size >= lim.rlim_cur) {
        return std::string(std::strerror(EFBIG)) + " (the file-size limit of this process, " +
               "ulimit -f, is " + std::to_string(lim.rlim_cur) + " bytes)";
    }
    struct statvfs fsys {};
    const fs::path folder = tmp.has_parent_path() ? tmp.parent_path() : fs::path(".");
    if (writer_failed && ::statvfs(folder.c_str(), &fsys) == 0 && fsys.f_blocks > 0 &&
        fsys.f_bavail == 0)
        return std::strerror(ENOSPC);
    return "";
}

// Replaces every occurrence of the temporary's name in a message by the final name: the user
// never asked for "*.tmp-*" files.
std::string with_final_name(std::string what, const fs::path& tmp, const fs::path& path) {
    const std::string from = tmp.string(), to = path.string();
    for (std::size_t at = 0; (at = what.find(from, at)) != std::string::npos; at += to.size())
        what.replace(at, from.size(), to);
    return what;
}

// Runs a writer on a temporary and checks the result is whole. A runtime failure (the disk
// full, a quota, the file-size limit, a library's write error) becomes RuntimeFailure "could not
// write '<path>': <reason>", the final name in place of the temporary's; other errors (input,
// memory and time bounds) pass unchanged.
void write_whole(const fs::path& tmp, const fs::path& path,
                 const std::function<void(const fs::path&)>& write) {
    const std::string prefix = "could not write '" + path.string() + "': ";
    try {
        write(tmp);
    } catch (const fs::filesystem_error& e) {
        const std::string cut = cut_reason(tmp, true);
        throw RuntimeFailure(prefix + (cut.empty() ? e.code().message() : cut));
    } catch (const RuntimeFailure& e) {
        const std::string what = with_final_name(e.what(), tmp, path);
        if (what.rfind(prefix, 0) == 0) throw RuntimeFailure(what);  // a nested writer's
        const std::string cut = cut_reason(tmp, true);
        throw RuntimeFailure(prefix + (cut.empty() ? what : cut + " (" + what + ")"));
    }
    if (const std::string cut = cut_reason(tmp, false); !cut.empty())
        throw RuntimeFailure(prefix + cut);
}

}  // namespace

void remove_pending_temporaries() noexcept {
    for (TempSlot* s = g_slots.load(); s; s = s->next) {
        if (s->state.load() == TempSlot::kLive) ::unlink(s->path.c_str());
    }
}

void write_file_atomic(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    check_output_path(path, "output");
    const fs::path tmp = temp_sibling(path);
    const TempGuard guard(tmp);
    try {
        write_whole(tmp, path, write);
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

namespace {
std::atomic<int> g_fail_rename_index{-1};

std::string list_paths(const std::vector<fs::path>& paths) {
    std::string s;
    for (const auto& p : paths) s += (s.empty() ? "" : ", ") + p.string();
    return s;
}
}  // namespace

void StagedFiles::fail_rename_for_test(int index) { g_fail_rename_index = index; }

StagedFiles::~StagedFiles() {
    if (!committed_) {
        for (const auto& t : temps_) {
            std::error_code ec;
            fs::remove(t, ec);
        }
    }
    for (void* slot : slots_) release_temp(static_cast<TempSlot*>(slot));
}

void StagedFiles::stage(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    check_output_path(path, "output");
    const std::vector<std::string> keys = same_file_keys(path);
    for (const std::string& key : keys) {
        if (final_keys_.count(key)) {
            throw invalid_field("output", "'" + path.string() + "'",
                                "is written twice by this run: two outputs must have different "
                                "names");
        }
    }
    final_keys_.insert(keys.begin(), keys.end());
    const fs::path tmp = temp_sibling(path);
    temps_.push_back(tmp);
    finals_.push_back(path);
    slots_.push_back(register_temp(tmp));
    write_whole(tmp, path, write);
}

void StagedFiles::stage_bytes(const fs::path& path, std::string_view bytes) {
    stage(path, [&](const fs::path& tmp) { write_bytes(tmp, bytes); });
}

void StagedFiles::commit() {
    const int fail_at = g_fail_rename_index.exchange(-1);
    // Existing files under the final names are moved aside first, so a failure can restore them.
    std::vector<fs::path> backups(finals_.size());
    std::vector<fs::path> renamed;
    std::size_t i = 0;
    std::string failure;
    try {
        for (; i < temps_.size(); ++i) {
            std::error_code ec;
            if (fs::exists(finals_[i], ec) && !fs::is_directory(finals_[i], ec)) {
                backups[i] = temp_sibling(finals_[i]);
                fs::rename(finals_[i], backups[i]);
            }
            if (static_cast<int>(i) == fail_at) {
                throw fs::filesystem_error("injected failure (test)", temps_[i], finals_[i],
                                           std::make_error_code(std::errc::io_error));
            }
            fs::rename(temps_[i], finals_[i]);
            renamed.push_back(finals_[i]);
        }
    } catch (const fs::filesystem_error& e) {
        failure = e.code().message();
    }
    if (failure.empty()) {
        for (const auto& b : backups) {
            std::error_code ec;
            if (!b.empty()) fs::remove(b, ec);
        }
        committed_ = true;
        return;
    }
    // Roll back: remove what was renamed, restore the old files, drop the temporaries.
    for (const auto& r : renamed) {
        std::error_code ec;
        fs::remove(r, ec);
    }
    for (std::size_t k = 0; k < backups.size(); ++k) {
        std::error_code ec;
        if (!backups[k].empty()) fs::rename(backups[k], finals_[k], ec);
    }
    const std::string what = "could not write '" + finals_[i].string() + "' (" + failure + ")";
    throw RuntimeFailure(
        what + "; " +
        (renamed.empty() ? std::string("no other output had been written")
                         : "removed the " + std::to_string(renamed.size()) +
                               " output(s) already written (" + list_paths(renamed) + ")") +
        ", earlier files under these names are restored: nothing of this run was kept");
}

}  // namespace pinmask
