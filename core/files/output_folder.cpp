#include "core/files/output_folder.hpp"

#include <system_error>
#include <utility>

#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"

namespace pinmask {
namespace fs = std::filesystem;

CreatedOutputFolder::CreatedOutputFolder(fs::path path, std::string flag)
    : path_(std::move(path)), flag_(std::move(flag)) {
    check_output_folder(path_, flag_);
}

void CreatedOutputFolder::create() {
    // The levels that do not exist yet, outermost first: exactly those are removed on failure.
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = fs::absolute(path_, ec).lexically_normal(); !p.empty(); p = p.parent_path()) {
        if (p.filename().empty()) {  // a trailing separator: "out/" names "out"
            if (p == p.parent_path()) break;
            continue;
        }
        if (fs::exists(fs::symlink_status(p, ec))) break;
        missing.insert(missing.begin(), p);
        if (p == p.parent_path()) break;
    }
    for (const fs::path& p : missing) {
        const bool made = fs::create_directory(p, ec);
        if (ec) {
            throw RuntimeFailure(flag_ + ": cannot create the folder '" + p.string() +
                                 "': " + ec.message());
        }
        if (made) created_.push_back(p);
    }
    // Another process may have made it meanwhile; what matters is that it is a folder now.
    check_output_folder(path_, flag_);
}

CreatedOutputFolder::~CreatedOutputFolder() {
    std::error_code ec;
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
        if (!fs::is_directory(*it, ec) || !fs::is_empty(*it, ec)) break;
        fs::remove(*it, ec);
    }
}

}  // namespace pinmask
