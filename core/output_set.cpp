#include "core/output_set.hpp"

#include <unistd.h>

#include <atomic>
#include <mutex>
#include <system_error>

#include "core/error.hpp"

namespace pinmask {
namespace fs = std::filesystem;
namespace {

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}

std::atomic<bool> g_protection{false};

std::vector<fs::path>& protected_inputs() {
    static std::vector<fs::path> inputs;
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

const fs::path* find_protected(const fs::path& path) {
    for (const fs::path& in : protected_inputs()) {
        if (same_file(in, path)) return &in;
    }
    return nullptr;
}

}  // namespace

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
    protected_inputs().clear();
}

void protect_input(const fs::path& path) {
    if (!g_protection) return;
    std::error_code ec;
    if (path.empty() || !fs::exists(path, ec)) return;
    std::lock_guard lock(registry_mutex());
    if (find_protected(path) == nullptr) protected_inputs().push_back(canonical_or_absolute(path));
}

void check_output_path(const fs::path& path, const std::string& flag) {
    if (path.empty()) throw invalid_field(flag, "''", "an output name must not be empty");
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        throw bad_output(flag, path, "is an existing directory, not a file name");
    }
    std::lock_guard lock(registry_mutex());
    if (const fs::path* in = find_protected(path)) {
        throw bad_output(flag, path,
                         "would overwrite the input '" + in->string() + "' of this run");
    }
}

void plan_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    std::vector<const NamedPath*> seen;
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
        for (const NamedPath& in : inputs) {
            if (!in.path.empty() && same_file(in.path, out.path)) {
                throw bad_output(out.flag, out.path,
                                 "is also the input " + in.flag + " ('" + in.path.string() +
                                     "'): an output must not replace an input of the same run");
            }
        }
        for (const NamedPath* other : seen) {
            if (same_file(other->path, out.path)) {
                throw bad_output(out.flag, out.path,
                                 "is also the output " + other->flag +
                                     ": two outputs of one run must have different names");
            }
        }
        seen.push_back(&out);
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

}  // namespace pinmask
