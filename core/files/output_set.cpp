#include "core/files/output_set.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>
#include <unordered_map>
#include <unordered_set>

#include "core/errors/error.hpp"
#include "core/files/input_file.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}

std::atomic<bool> g_protection{false};

// A protected input is found by its identity (device and inode) and by its canonical path, so
// a lookup is one stat and one hash, whatever the number of inputs (a batch of 10,000
// captures).
struct ProtectedInputs {
    std::unordered_map<std::string, fs::path> by_key;
};
ProtectedInputs& protected_inputs() {
    static ProtectedInputs inputs;
    return inputs;
}

fs::path canonical_or_absolute(const fs::path& p) {
    std::error_code ec;
    fs::path c = fs::weakly_canonical(p, ec);
    if (ec) c = fs::absolute(p, ec).lexically_normal();
    return c;
}

InvalidInput bad_output(const std::string& flag, const fs::path& path, const std::string& rule) {
    return invalid_field(flag, "'" + path.string() + "'", rule);
}

// The nearest ancestor of p that exists (p's parent first; "." for a bare file name).
fs::path nearest_existing_parent(const fs::path& p) {
    fs::path parent = canonical_or_absolute(p).parent_path();
    std::error_code ec;
    while (!parent.empty() && !fs::exists(parent, ec)) {
        if (parent == parent.parent_path()) break;
        parent = parent.parent_path();
    }
    return parent;
}

// Why no file can be created in `folder` (which exists), or "" when one can. access() trusts
// the permission bits; some folders refuse every new name whatever their bits (/proc, /sys,
// a full or read-only mount seen through a writable bind): a real create-and-unlink finds
// them before any work, instead of a raw "cannot open ... for writing" after it.
std::string create_problem(const fs::path& folder) {
    static std::atomic<unsigned> serial{0};
    const fs::path probe = folder / (".pinmask-probe-" + std::to_string(::getpid()) + "-" +
                                     std::to_string(serial.fetch_add(1)));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) return std::strerror(errno);
    ::close(fd);
    ::unlink(probe.c_str());
    return "";
}

// Identity keys of a path: "i<dev>:<ino>" when it exists, and "p<canonical path>" always.
std::string inode_key(const fs::path& p) {
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0) return "";
    return "i" + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
}
std::string path_key(const fs::path& p) { return "p" + canonical_or_absolute(p).string(); }

const fs::path* find_protected(const fs::path& path) {
    auto& map = protected_inputs().by_key;
    if (map.empty()) return nullptr;
    for (const std::string& key : {inode_key(path), path_key(path)}) {
        if (key.empty()) continue;
        if (const auto it = map.find(key); it != map.end()) return &it->second;
    }
    return nullptr;
}

}  // namespace

std::vector<std::string> same_file_keys(const fs::path& p) {
    std::vector<std::string> keys;
    if (std::string key = inode_key(p); !key.empty()) keys.push_back(std::move(key));
    keys.push_back(path_key(p));
    return keys;
}

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        const bool eq = fs::equivalent(a, b, ec);
        if (!ec) return eq;
    }
    return canonical_or_absolute(a) == canonical_or_absolute(b);
}

void enable_input_protection() { g_protection = true; }

void reset_input_protection() {
    std::lock_guard lock(registry_mutex());
    g_protection = false;
    protected_inputs().by_key.clear();
}

void protect_input(const fs::path& path) {
    if (!g_protection) return;
    std::error_code ec;
    if (path.empty() || !fs::exists(path, ec)) return;
    std::lock_guard lock(registry_mutex());
    const fs::path canonical = canonical_or_absolute(path);
    auto& map = protected_inputs().by_key;
    if (const std::string key = inode_key(path); !key.empty()) map.emplace(key, canonical);
    map.emplace(path_key(path), canonical);
}

void release_input(const fs::path& path) {
    std::lock_guard lock(registry_mutex());
    for (const std::string& key : same_file_keys(path)) protected_inputs().by_key.erase(key);
}

void check_output_path(const fs::path& path, const std::string& flag) {
    if (path.empty()) throw invalid_field(flag, "''", "an output name must not be empty");
    if (path.native().find('\0') != std::string::npos)  // the system would stop at the NUL
        throw bad_output(flag, path, "the name holds a NUL byte, which no file name can");
    std::error_code ec;
    // Temporary siblings add ".tmp-<pid>-<n>" (twice when a writer nests) to the name: a name
    // that leaves no room for them fails late with the system's raw message, so it is refused
    // here, with the limit of the folder's file system.
    const std::string name = path.filename().string();
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    long name_max = ::pathconf(fs::exists(folder, ec) ? folder.c_str() : ".", _PC_NAME_MAX);
    if (name_max <= 0) name_max = 255;
    constexpr long kTempRoom = 64;
    if (static_cast<long>(name.size()) + kTempRoom > name_max) {
        throw bad_output(flag, path,
                         "its file name has " + std::to_string(name.size()) +
                             " bytes; this file system allows " + std::to_string(name_max) +
                             " and pinmask keeps " + std::to_string(kTempRoom) +
                             " of them for its temporary names: use a shorter name");
    }
    const fs::file_status st = fs::status(path, ec);  // follows a symlink to what it names
    if (fs::is_directory(st)) {
        throw bad_output(flag, path, "is an existing directory, not a file name");
    }
    // Outputs are renamed into place: over a device, a pipe or a socket that would replace the
    // special file itself (as root, /dev/null) with a regular file. Only regular files (or new
    // names) are written.
    if (fs::exists(st) && !fs::is_regular_file(st)) {
        throw bad_output(flag, path,
                         std::string("is ") + special_file_kind(st) +
                             ": pinmask writes only regular files (give a file name)");
    }
    // The folder it goes into, when it exists, must take new files: probed once per process.
    const fs::path folder_now = fs::absolute(path, ec).lexically_normal().parent_path();
    if (fs::is_directory(folder_now, ec)) {
        static std::mutex probed_mutex;
        static std::unordered_set<std::string> probed;
        std::lock_guard probe_lock(probed_mutex);
        if (!probed.count(folder_now.string())) {
            if (const std::string why = create_problem(folder_now); !why.empty()) {
                throw bad_output(
                    flag, path,
                    "no file can be created in its folder '" + folder_now.string() + "': " + why);
            }
            probed.insert(folder_now.string());
        }
    }
    std::lock_guard lock(registry_mutex());
    if (const fs::path* in = find_protected(path)) {
        throw bad_output(flag, path,
                         "would overwrite the input '" + in->string() + "' of this run");
    }
}

void plan_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    // Every path is keyed once (identity and canonical path), so planning N outputs against M
    // inputs costs O(N + M) lookups, not N x M comparisons.
    std::unordered_map<std::string, const NamedPath*> input_keys, output_keys;
    for (const NamedPath& in : inputs) {
        if (in.path.empty()) continue;
        for (const std::string& key : {inode_key(in.path), path_key(in.path)})
            if (!key.empty()) input_keys.emplace(key, &in);
    }
    for (const NamedPath& out : outputs) {
        if (out.path.empty()) {
            // "-o" is every command's required output; other empty names are optional outputs
            // that were not asked for.
            if (out.flag == "-o") throw invalid_field("-o", "''", "an output name is required");
            continue;
        }
        check_output_path(out.path, out.flag);
        if (out.path.filename().empty() || out.path.filename() == "." ||
            out.path.filename() == "..") {
            throw bad_output(out.flag, out.path, "names a directory, not a file");
        }
        for (const std::string& key : {inode_key(out.path), path_key(out.path)}) {
            if (key.empty()) continue;
            if (const auto it = input_keys.find(key); it != input_keys.end()) {
                const NamedPath& in = *it->second;
                throw bad_output(out.flag, out.path,
                                 "is also the input " + in.flag + " ('" + in.path.string() +
                                     "'): an output must not replace an input of the same run");
            }
            if (const auto it = output_keys.find(key); it != output_keys.end()) {
                throw bad_output(out.flag, out.path,
                                 "is also the output " + it->second->flag +
                                     ": two outputs of one run must have different names");
            }
        }
        for (const std::string& key : {inode_key(out.path), path_key(out.path)})
            if (!key.empty()) output_keys.emplace(key, &out);
        const fs::path parent = nearest_existing_parent(out.path);
        std::error_code ec;
        if (!parent.empty() && !fs::is_directory(parent, ec)) {
            throw bad_output(out.flag, out.path,
                             "its folder '" + parent.string() + "' is a file, not a directory");
        }
        if (!out.folder_created && parent != canonical_or_absolute(out.path).parent_path()) {
            throw bad_output(out.flag, out.path,
                             "its folder '" + out.path.parent_path().string() +
                                 "' does not exist (create it first)");
        }
        if (!parent.empty() && ::access(parent.c_str(), W_OK | X_OK) != 0) {
            throw bad_output(out.flag, out.path,
                             "its folder '" + parent.string() + "' is not writable");
        }
    }
    enable_input_protection();
    for (const NamedPath& in : inputs) protect_input(in.path);
}

void check_output_folder(const fs::path& path, const std::string& flag) {
    if (path.empty()) throw invalid_field(flag, "''", "an output folder is required");
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st) || fs::is_directory(st)) return;
    throw invalid_field(flag, path.string(),
                        std::string("is ") +
                            (fs::is_regular_file(st) ? "a file" : special_file_kind(st)) +
                            "; give a folder (created when missing)");
}

}  // namespace pinmask
