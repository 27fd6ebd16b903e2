// The process-wide memory budget, end to end: every command runs under a small
// PINMASK_MEMORY_LIMIT, on a workload that fits and on one that would not, and the child's peak
// resident set (wait4's rusage, ru_maxrss) must stay under the limit plus kCodeMargin. Requests
// beyond the bound must be refused (exit 2) before their memory is touched, whatever the
// command and whichever allocation is first.
//
// kCodeMargin = 64 MiB: what the bound does not govern. The executable and its shared libraries
// (FFTW, CGAL, Cairo, fontconfig, libtiff, libpng: ~10 MB resident), their caches (fontconfig's
// font list, FFTW plans), and the allocations below kChargeThresholdBytes (4 MiB) that are
// never charged. Measured: every command here peaks at 9 to 20 MB on small inputs, so 64 MiB
// leaves room for the uncharged small allocations without hiding a 100 MB working set.
//
// Under PINMASK_SANITIZED=1 (AddressSanitizer) the RSS comparison is skipped and said: ASan's
// shadow memory (1/8 of the heap), its redzones and its quarantine of freed blocks (256 MB by
// default) inflate the resident set by a factor, not a margin. The exit codes, messages and
// the absence of output files are still checked there.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_run.hpp"

using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

constexpr double kMiB = 1024.0 * 1024.0;
constexpr double kCodeMargin = 64 * kMiB;

const fs::path kSource = PINMASK_SOURCE_DIR;
const fs::path kCorpus = kSource / "tests" / "bad-inputs";
const fs::path kMask = kSource / "fuzz/corpus/mask_json/small.mask.json";
const fs::path kCapture = kSource / "fuzz/corpus/image/cap.npy";

bool sanitized() { return std::getenv("PINMASK_SANITIZED") != nullptr; }

struct Measured {
    int exit_code = -1;
    double peak_bytes = 0;
    std::string err;
};

// Runs pinmask with `args` (split on spaces; no quoting needed for these paths) in `cwd`, with
// PINMASK_MEMORY_LIMIT = limit (unset when empty), and returns its exit code, peak RSS and stderr.
Measured run_measured(const std::string& args, const std::string& limit, const fs::path& cwd) {
    std::vector<std::string> words{PINMASK_EXE};
    std::istringstream in(args);
    for (std::string w; in >> w;) words.push_back(w);
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    const fs::path err_path = cwd / ".stderr";
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        if (::chdir(cwd.c_str()) != 0) ::_exit(120);
        if (limit.empty()) {
            ::unsetenv("PINMASK_MEMORY_LIMIT");
        } else {
            ::setenv("PINMASK_MEMORY_LIMIT", limit.c_str(), 1);
        }
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int null = ::open("/dev/null", O_RDWR);
        if (err < 0 || null < 0) ::_exit(121);
        ::dup2(null, 0);
        ::dup2(null, 1);
        ::dup2(err, 2);
        ::execv(argv[0], argv.data());
        ::_exit(122);
    }
    int status = 0;
    struct rusage ru {};
    REQUIRE(::wait4(pid, &status, 0, &ru) == pid);
    Measured m;
    m.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    m.peak_bytes = double(ru.ru_maxrss) * 1024.0;  // Linux: kilobytes
    m.err = slurp(err_path);
    fs::remove(err_path);
    return m;
}

double limit_bytes(const std::string& limit) {
    const double v = std::stod(limit);
    switch (limit.back()) {
        case 'G':
            return v * 1024 * kMiB;
        case 'M':
            return v * kMiB;
        default:
            return v;
    }
}

struct Case {
    std::string name;
    std::string args;
    std::string limit;
    int exit_code;        // expected
    std::string message;  // fragment of stderr when exit_code == 2
};

void check_case(const Case& c, const fs::path& dir) {
    INFO(c.name << ": pinmask " << c.args << " (PINMASK_MEMORY_LIMIT=" << c.limit << ")");
    const Measured m = run_measured(c.args, c.limit, dir);
    INFO("stderr: " << m.err);
    CHECK(m.exit_code == c.exit_code);
    if (!c.message.empty()) CHECK(m.err.find(c.message) != std::string::npos);
    MESSAGE(c.name << ": peak RSS " << m.peak_bytes / kMiB << " MiB under a "
                   << (c.limit.empty() ? std::string("default") : c.limit) << " bound");
    if (sanitized()) return;  // ASan inflates RSS by a factor (see the top of the file)
    const double bound = c.limit.empty() ? 100 * kMiB : limit_bytes(c.limit);
    CHECK(m.peak_bytes <= bound + kCodeMargin);
}

}  // namespace

TEST_CASE("every command stays under PINMASK_MEMORY_LIMIT plus the code margin") {
    if (sanitized()) MESSAGE("sanitized build: peak RSS is reported, not compared (ASan shadow)");
    TempDir t("memory");
    const fs::path d = t.path;
    const std::string mask = kMask.string(), cap = kCapture.string();
    // A 100k-pinhole mask for the dark-tone export (0.1 s to generate).
    REQUIRE(pinmask::test::run_cli("generate --grid 1000 --holes 100000 --spacing 1 --tiles 1 "
                                   "--pixels-per-cell 1 -o big.mask.json",
                                   d)
                .exit_code == 0);
    const std::vector<Case> cases = {
        // Workloads that fit: they must succeed under the small bound.
        {"design", "design --preset paper", "100M", 0, ""},
        {"generate", "generate -o g.mask.json", "100M", 0, ""},
        {"psf", "psf " + mask + " -o p.tiff --npy", "100M", 0, ""},
        {"simulate", "simulate " + mask + " --full-sensor -o s.tiff", "100M", 0, ""},
        {"decode", "decode " + cap + " --mask " + mask + " -o d.png --stats d.json", "100M", 0, ""},
        {"score", "score " + mask, "100M", 0, ""},
        {"compare", "compare " + mask + " g.mask.json --report r.pdf", "100M", 0, ""},
        {"export", "export " + mask + " -o e", "100M", 0, ""},
        {"check", "check " + mask, "100M", 0, ""},
        {"search", "search --grid 8 --holes 6 --evals 20 -o sr", "100M", 0, ""},
        // Near the bound: a 1000 x 1000 full-sensor capture (8 MB a plane) fits; decoding it
        // whole (--crop none, ~0.18 GiB of solver planes) does not and is refused.
        {"simulate 1000 x 1000",
         "simulate " + mask + " --full-sensor --sensor 1000x1000 -o mid.tiff", "100M", 0, ""},
        {"decode 1000 x 1000, one period", "decode mid.tiff --mask " + mask + " -o mid.png", "100M",
         0, ""},
        {"decode 1000 x 1000 whole", "decode mid.tiff --mask " + mask + " --crop none -o big.png",
         "100M", 2, "memory bound"},
        // Workloads beyond the bound: refused before their memory is touched.
        {"decode 16000^2 zero PNG (249 KB file, 2 GB of doubles)",
         "decode " + (kCorpus / "capture-zeros-16000.png").string() + " --mask " + mask +
             " -o big.png",
         "2500M", 2, "kMaxImageSamples"},
        {"decode 16000^2 zero PNG, default bound",
         "decode " + (kCorpus / "capture-zeros-16000.png").string() + " --mask " + mask +
             " -o big.png",
         "", 2, "kMaxImageSamples"},
        {"decode 4000^2 zero PNG (128 MB of doubles)",
         "decode " + (kCorpus / "capture-zeros-4000.png").string() + " --mask " + mask +
             " -o big.png",
         "100M", 2, "memory bound"},
        {"simulate a 20000 x 20000 sensor",
         "simulate " + mask + " --full-sensor --sensor 20000x20000 -o big.tiff", "100M", 2,
         "memory bound"},
        {"psf of a 4096 grid",
         "psf " + (kCorpus / "mask-grid-4096.mask.json").string() + " -o big.tiff", "100M", 2,
         "memory bound"},
        {"export a 100k-pinhole dark-tone mask",
         "export big.mask.json --tone dark --no-psf --format svg,gds -o big", "100M", 2,
         "memory bound"},
        {"search on a 1024 grid", "search --grid 1024 --holes 20 --evals 5 -o bigsearch", "100M", 2,
         "memory bound"},
        // A 30 KB OASIS file whose 10^4 records reuse one 2,025-square repetition (20 million
        // squares): every ring made is charged, not only each record's.
        {"check an OASIS file of reused repetitions",
         "check " + (kCorpus / "layout-reused-repetition.oas").string(), "1G", 2, "memory bound"},
        // 3.3 million squares that the reader alone fits under 1 GiB, but not the whole check
        // (its copies of the rings peaked at 1.74 GB): charged at what a ring costs through it.
        {"check a 300,000-entry OASIS repetition reused 10 times",
         "check " + (kCorpus / "layout-repetition-300k-entries.oas").string(), "1G", 2,
         "memory bound"},
        // A million rings from a 1000 x 1000 GDSII AREF under 256 MiB (551 MB before).
        {"check a GDSII AREF of a million squares",
         "check " + (kCorpus / "layout-gds-aref-expands.gds").string(), "256M", 2, "memory bound"},
    };
    for (const Case& c : cases) check_case(c, d);
    // Nothing of the refused runs was written.
    for (const char* name : {"big.png", "big.tiff", "big", "bigsearch"}) {
        CHECK_FALSE(fs::exists(d / name));
    }
}

// Inputs whose size sets a container's size are charged (or bounded) before the container
// grows, under a 1 GiB bound: a search configuration listing 30,000 re-rank scenes (19 GB when
// uncharged), a checkpoint whose log has 300,000 entries (resumed in minutes before the bound),
// a PSF whose sidecar is a link to /dev/zero (read to 16.8 GB before the type check).
TEST_CASE("inputs that grow containers are charged or bounded before they grow (1 GiB bound)") {
    TempDir t("memory-grow");
    const fs::path d = t.path;
    // A real configuration and checkpoint to edit: a 16-grid random search of 3000 evaluations.
    const std::string run =
        "search --grid 16 --holes 20 --evals 3000 --threads 1 --seed 1 --strategy random "
        "--no-rerank --checkpoint ck.json --checkpoint-every 1000";
    REQUIRE(pinmask::test::run_cli(run + " -o base", d).exit_code == 0);
    nlohmann::json config = nlohmann::json::parse(slurp(d / "base" / "search.config.json"));
    config["rerank_scenes"] = std::vector<std::string>(30000, "letter-R");
    std::ofstream(d / "scenes.json") << config.dump();
    nlohmann::json ck = nlohmann::json::parse(slurp(d / "ck.json"));
    nlohmann::json log = nlohmann::json::array();
    for (int e = 1; e <= 300000; ++e) log.push_back({e, nullptr});
    ck["chains"][0]["log"] = log;
    {  // its checksum recomputed (FNV-1a 64 of the text with the value zeroed), as a forger would
        ck["checksum"] = "0000000000000000";
        std::string text = ck.dump();
        unsigned long long h = 0xcbf29ce484222325ULL;
        for (const unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ULL;
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", h);
        text.replace(text.find("0000000000000000", text.rfind("\"checksum\"")), 16, hex);
        std::ofstream(d / "long-log.json") << text;
    }
    fs::copy_file(kSource / "fuzz/corpus/image/psf_box.tiff", d / "z.tiff");
    fs::create_symlink("/dev/zero", d / "z.json");
    const std::vector<Case> cases = {
        {"search with 30,000 re-rank scenes", "search --config scenes.json -o s", "1G", 2,
         "30000 re-rank scenes of 128 x 128"},
        {"resume a checkpoint whose log has 300,000 entries",
         run.substr(0, run.find("--checkpoint ")) + "--checkpoint ck2.json --checkpoint-every " +
             "1000 --resume long-log.json -o r",
         "1G", 2, "has 300000 entries"},
        {"decode with a PSF sidecar linked to /dev/zero",
         "decode " + kCapture.string() + " --psf z.tiff -o zz.png", "1G", 2,
         "is a character device"},
    };
    for (const Case& c : cases) check_case(c, d);
    for (const char* name : {"s", "r", "zz.png", "ck2.json"}) CHECK_FALSE(fs::exists(d / name));
}
