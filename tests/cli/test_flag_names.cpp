// The command line's table of field spellings (cli/options/flag_names): every field a library
// names in a message (core/errors/field_names.hpp: field_ref("...")) has a flag, the table is
// sorted and unique (flag_spelling looks rows up by binary search), and spell_flags turns a library
// message into what the command line prints. Also: no library source spells a flag itself.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/options/flag_names.hpp"
#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"

namespace {

namespace fs = std::filesystem;

// The folders of the libraries (everything the faces cli/ and python/ link).
const char* const kLibraryFolders[] = {"core",     "design", "decode", "export",
                                       "optimize", "io",     "report", "bench"};

std::vector<fs::path> library_sources() {
    std::vector<fs::path> out;
    for (const char* folder : kLibraryFolders) {
        const fs::path dir = fs::path(PINMASK_SOURCE_DIR) / folder;
        REQUIRE(fs::is_directory(dir));
        for (const auto& e : fs::recursive_directory_iterator(dir)) {
            const std::string ext = e.path().extension().string();
            if (e.is_regular_file() && (ext == ".cpp" || ext == ".hpp")) out.push_back(e.path());
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every name in a field_ref("name") call, with the first file that names it.
std::map<std::string, std::string> referenced_fields() {
    static const std::regex kRef(R"re(field_ref\(\s*"([^"]*)"\s*\))re");
    std::map<std::string, std::string> out;
    for (const fs::path& p : library_sources()) {
        const std::string text = slurp(p);
        for (auto it = std::sregex_iterator(text.begin(), text.end(), kRef);
             it != std::sregex_iterator(); ++it)
            out.emplace((*it)[1].str(), p.string());
    }
    return out;
}

// The code of a line without its // comment (a "//" inside a string literal is kept).
std::string code_of(const std::string& line) {
    bool in_string = false;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        if (line[i] == '\\' && in_string) {
            ++i;
        } else if (line[i] == '"') {
            in_string = !in_string;
        } else if (!in_string && line[i] == '/' && line[i + 1] == '/') {
            return line.substr(0, i);
        }
    }
    return line;
}

}  // namespace

TEST_CASE("every field a library names in a message has a command-line flag") {
    const std::map<std::string, std::string> fields = referenced_fields();
    // The scan sees the libraries' references (two of them, as a check of the scan).
    CHECK(fields.count("robust") == 1);
    CHECK(fields.count("chord_tolerance_m") == 1);
    for (const auto& entry : fields) {
        // Copies: clang cannot capture a structured binding in INFO's lambda.
        const std::string& field = entry.first;
        const std::string& file = entry.second;
        INFO("field_ref(\"" << field << "\") in " << file);
        CHECK(pinmask::is_field_name(field));
        CHECK(pinmask::cli::flag_spelling(field).has_value());
    }
}

TEST_CASE("the flag table is sorted by field, unique, and spells flags") {
    const auto rows = pinmask::cli::flag_rows();
    REQUIRE(rows.size() > 1);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        INFO("row " << i << ": " << rows[i].first << " -> " << rows[i].second);
        CHECK(pinmask::is_field_name(rows[i].first));
        CHECK(rows[i].second.substr(0, 2) == "--");
        if (i > 0) CHECK(rows[i - 1].first < rows[i].first);  // sorted, hence unique
        // Every row is found by the binary search.
        CHECK(pinmask::cli::flag_spelling(rows[i].first) == std::string(rows[i].second));
    }
    CHECK_FALSE(pinmask::cli::flag_spelling("no_such_field").has_value());
}

TEST_CASE("spell_flags turns the library's field references into flags") {
    using pinmask::field_ref;
    using pinmask::cli::spell_flags;
    const pinmask::InvalidInput e =
        pinmask::invalid_field(field_ref("chord_tolerance_m"), "-5 nm", "must be > 0");
    CHECK(spell_flags(e.what()) == "--chord-tol = -5 nm: must be > 0");
    // Two references in one message, and a field set by a flag with its value.
    CHECK(spell_flags(field_ref("checkpoint_every") + ": needs " + field_ref("checkpoint") +
                      " FILE") == "--checkpoint-every: needs --checkpoint FILE");
    CHECK(spell_flags("only with " + field_ref("exact_geometry")) == "only with --geometry exact");
    CHECK(spell_flags(field_ref("robust") + " size = 1 um: bad") == "--robust size = 1 um: bad");
    // A field without a flag is spelled bare; backquotes around anything else stay.
    CHECK(spell_flags("key " + field_ref("no_such_field") + " x") == "key no_such_field x");
    CHECK(spell_flags("run `pinmask check` for details") == "run `pinmask check` for details");
    CHECK(spell_flags("no reference") == "no reference");
}

TEST_CASE("no library source spells a command-line flag in a string literal") {
    std::vector<std::string> hits;
    for (const fs::path& p : library_sources()) {
        std::istringstream in(slurp(p));
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            if (code_of(line).find("\"--") != std::string::npos)
                hits.push_back(p.string() + ":" + std::to_string(number) + ": " + line);
        }
    }
    std::string all;
    for (const std::string& h : hits) all += h + "\n";
    INFO(all);
    CHECK(hits.empty());
}
