// `pinmask decode --batch` end to end: three simulated captures (generate, simulate
// with three seeds) decoded as a batch give the same bytes as `pinmask decode` on each alone,
// for a directory and a list file; bad inputs exit 2 naming the flag and write nothing.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/image/image_io.hpp"
#include "tests/core/dng_writer.hpp"
#include "tests/core/jpeg_writer.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kFlags = " --method tikhonov --lambda 1e-3 ";

// m.mask.json and caps/c1..c3.tiff (simulate with seeds 1..3) in `dir`.
void make_captures(const TempDir& dir) {
    REQUIRE(run_cli("generate --grid 8 --holes 6 --tiles 2 --pixels-per-cell 4 --seed 3 -o " +
                    dir / "m.mask.json")
                .exit_code == 0);
    fs::create_directory(dir.path / "caps");
    for (int s = 1; s <= 3; ++s) {
        const auto r =
            run_cli("simulate " + dir / "m.mask.json" + " --scene letter-R --snr 30 --seed " +
                    std::to_string(s) + " -o " + dir / ("caps/c" + std::to_string(s) + ".tiff"));
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
    }
}

// The number of files in `d`; none may be a temporary.
int file_count(const fs::path& d) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(d)) {
        CHECK(e.path().string().find(".tmp") == std::string::npos);
        ++n;
    }
    return n;
}

}  // namespace

TEST_CASE("decode --batch: each output has the bytes of decoding that capture alone") {
    TempDir dir("cli-decode-batch");
    make_captures(dir);
    fs::create_directory(dir.path / "single");
    for (const std::string fmt : {"tiff", "png"}) {
        const std::string flags = " --method wiener --nsr 1e-3 ";
        const fs::path out = dir.path / ("batch-" + fmt);
        fs::create_directory(out);
        const auto r = run_cli("decode --batch caps --mask m.mask.json" + flags +
                                   "--batch-stats --batch-format " + fmt + " -o " + out.string(),
                               dir.path);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        const auto summary = nlohmann::json::parse(slurp(out / "batch-summary.json"));
        REQUIRE(summary["captures"].size() == 3);
        for (int s = 1; s <= 3; ++s) {
            const std::string stem = "c" + std::to_string(s);
            const std::string single = "single/" + stem + "." + fmt;
            REQUIRE(
                run_cli("decode caps/" + stem + ".tiff --mask m.mask.json" + flags + "-o " + single,
                        dir.path)
                    .exit_code == 0);
            CHECK(slurp(out / (stem + "." + fmt)) == slurp(dir.path / single));
            CHECK(fs::exists(out / (stem + ".stats.json")));
            CHECK(summary["captures"][s - 1]["input"] == "caps/" + stem + ".tiff");
        }
        CHECK(file_count(out) == 3 * 3 + 1);  // image, config, stats per capture; the summary
    }
    // A list file in another order and another method (the operator path): the same bytes too.
    {
        std::ofstream(dir.path / "list.txt") << "# captures\ncaps/c3.tiff\n\n  caps/c1.tiff\n";
        fs::create_directory(dir.path / "listed");
        const auto r =
            run_cli("decode --batch list.txt --mask m.mask.json" + kFlags + "-o listed", dir.path);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        for (const std::string stem : {"c3", "c1"}) {
            REQUIRE(run_cli("decode caps/" + stem + ".tiff --mask m.mask.json" + kFlags +
                                "-o single/" + stem + "-tik.tiff",
                            dir.path)
                        .exit_code == 0);
            CHECK(slurp(dir.path / ("listed/" + stem + ".tiff")) ==
                  slurp(dir.path / ("single/" + stem + "-tik.tiff")));
        }
        const auto summary = nlohmann::json::parse(slurp(dir.path / "listed/batch-summary.json"));
        CHECK(summary["captures"][0]["input"] == "caps/c3.tiff");
        CHECK(summary["captures"][1]["input"] == "caps/c1.tiff");
    }
}

TEST_CASE("decode --batch: a folder's JPEG and camera RAW captures are decoded too") {
    TempDir dir("cli-decode-batch-formats");
    make_captures(dir);
    // c1's counts as an 8-bit grey JPEG and as a DNG whose 2 x 2 Bayer blocks each hold them.
    const pinmask::Image cap = pinmask::read_image(dir.path / "caps/c1.tiff").image;
    const int rows = cap.rows(), cols = cap.cols();
    const double peak = cap.channels[0].maxCoeff();
    REQUIRE(peak > 0);
    std::vector<unsigned char> counts(static_cast<std::size_t>(rows) * cols);
    pinmask::test::DngSpec dng;
    dng.rows = 2 * rows;
    dng.cols = 2 * cols;
    dng.values.resize(static_cast<std::size_t>(dng.rows) * dng.cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const long q = std::lround(cap.channels[0](r, c) / peak * 255.0);
            counts[static_cast<std::size_t>(r) * cols + c] = static_cast<unsigned char>(q);
            for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b)
                    dng.values[static_cast<std::size_t>(2 * r + a) * dng.cols + 2 * c + b] =
                        static_cast<std::uint16_t>(64 + 10 * q);
        }
    fs::create_directory(dir.path / "mixed");
    pinmask::test::JpegSpec grey;
    grey.input = JCS_GRAYSCALE;
    std::ofstream(dir.path / "mixed/a.jpg", std::ios::binary)
        << pinmask::test::encode_jpeg(counts, rows, cols, grey);
    pinmask::test::write_dng(dir.path / "mixed/b.dng", dng);
    std::ofstream(dir.path / "mixed/notes.txt") << "not a capture\n";
    fs::create_directory(dir.path / "out");
    const auto r = run_cli("decode --batch mixed --mask m.mask.json" + kFlags + "-o out", dir.path);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto summary = nlohmann::json::parse(slurp(dir.path / "out/batch-summary.json"));
    REQUIRE(summary["captures"].size() == 2);
    CHECK(summary["captures"][0]["input"] == "mixed/a.jpg");
    CHECK(summary["captures"][1]["input"] == "mixed/b.dng");
    fs::create_directory(dir.path / "single");
    for (const std::string name : {"a.jpg", "b.dng"}) {
        const std::string stem = name.substr(0, 1);
        REQUIRE(run_cli("decode mixed/" + name + " --mask m.mask.json" + kFlags + "-o single/" +
                            stem + ".tiff",
                        dir.path)
                    .exit_code == 0);
        CHECK(slurp(dir.path / ("out/" + stem + ".tiff")) ==
              slurp(dir.path / ("single/" + stem + ".tiff")));
    }
}

TEST_CASE("decode --batch: bad inputs exit 2 naming the flag, nothing written") {
    TempDir dir("cli-decode-batch-bad");
    make_captures(dir);
    fs::create_directory(dir.path / "out");
    fs::create_directory(dir.path / "empty");
    std::ofstream(dir.path / "empty.txt") << "# nothing\n\n";
    std::ofstream(dir.path / "missing.txt") << "caps/c1.tiff\ncaps/nope.tiff\n";
    std::ofstream(dir.path / "twice.txt") << "caps/c1.tiff\ncaps/c1.tiff\n";
    fs::copy_file(dir.path / "caps/c2.tiff", dir.path / "c2.tiff");
    std::ofstream(dir.path / "clash.txt") << "caps/c2.tiff\nc2.tiff\n";
    // A capture whose name is not UTF-8 (the summary, JSON, could not record it), in a folder
    // and in a list; a list line with a NUL byte (the system would open its prefix).
    fs::create_directory(dir.path / "latin1");
    fs::copy_file(dir.path / "caps/c1.tiff", dir.path / "latin1/caf\xE9.tiff");
    std::ofstream(dir.path / "latin1.txt") << "caps/c1.tiff\nlatin1/caf\xE9.tiff\n";
    std::ofstream(dir.path / "nul.txt") << std::string("caps/c1.tiff\0.x\n", 16);
    const std::string m = " --mask m.mask.json ";
    struct Case {
        std::string args, flag;
    };
    const Case cases[] = {
        {"--batch empty" + m + "-o out", "--batch"},
        {"--batch empty.txt" + m + "-o out", "--batch"},
        {"--batch missing.txt" + m + "-o out", "--batch"},
        {"--batch twice.txt" + m + "-o out", "--batch"},
        {"--batch clash.txt" + m + "-o out", "--batch"},
        {"--batch latin1" + m + "-o out", "caf\\xE9.tiff: in latin1: the name is not UTF-8"},
        {"--batch latin1.txt" + m + "-o out", "the name is not UTF-8"},
        {"--batch nul.txt" + m + "-o out", "the line holds a NUL byte"},
        {"--batch no-such-dir" + m + "-o out", "--batch"},
        {"--batch caps" + m + "-o m.mask.json", "-o"},
        {"--batch caps" + m + "-o out --batch-format jpg", "--batch-format"},
        {"--batch caps" + m + "-o out --stats s.json", "--stats"},
        {"caps/c1.tiff --batch caps" + m + "-o out", "--batch"},
        {"--batch caps -o out", "--mask"},
    };
    for (const Case& c : cases) {
        const auto r = run_cli("decode " + c.args, dir.path);
        INFO(c.args, "\n", r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(c.flag) != std::string::npos);
        CHECK(fs::is_empty(dir.path / "out"));
    }
    // A capture that cannot be read, second of three: no file of any capture remains.
    std::ofstream(dir.path / "bad.npy") << "not an npy file";
    std::ofstream(dir.path / "bad.txt") << "caps/c1.tiff\nbad.npy\ncaps/c3.tiff\n";
    const auto r = run_cli("decode --batch bad.txt" + m + "-o out", dir.path);
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(fs::is_empty(dir.path / "out"));
    CHECK(run_cli("decode" + m + "-o out/x.tiff", dir.path).exit_code == 2);
}

TEST_CASE("decode --batch: a missing -o folder is created, and removed again when the run fails") {
    TempDir dir("cli-decode-batch-folder");
    make_captures(dir);
    const std::string m = " --mask m.mask.json" + kFlags;
    // Created with its missing parents; the files are those of an existing folder's run.
    fs::create_directory(dir.path / "existing");
    REQUIRE(run_cli("decode --batch caps" + m + "-o existing", dir.path).exit_code == 0);
    const auto r = run_cli("decode --batch caps" + m + "-o new/deeper/out/", dir.path);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(file_count(dir.path / "new/deeper/out") == file_count(dir.path / "existing"));
    for (const std::string stem : {"c1", "c2", "c3"})
        CHECK(slurp(dir.path / ("new/deeper/out/" + stem + ".tiff")) ==
              slurp(dir.path / ("existing/" + stem + ".tiff")));
    // A run that fails, before any work or on its second capture, leaves no folder behind: not
    // the one named, not the parents it made; an existing parent stays.
    std::ofstream(dir.path / "bad.npy") << "not an npy file";
    std::ofstream(dir.path / "bad.txt") << "caps/c1.tiff\nbad.npy\ncaps/c3.tiff\n";
    struct Case {
        std::string args, flag;
    };
    const Case cases[] = {
        {"--batch bad.txt" + m + "-o gone/a/b", "bad.npy"},
        {"--batch caps" + m + "-o gone/a --batch-format jpg", "--batch-format"},
        {"--batch caps --mask nope.mask.json -o gone", "nope.mask.json"},
        {"--batch bad.txt" + m + "-o new/fresh", "bad.npy"},
    };
    for (const Case& c : cases) {
        const auto f = run_cli("decode " + c.args, dir.path);
        INFO(c.args, "\n", f.err);
        CHECK(f.exit_code == 2);
        CHECK(f.err.find(c.flag) != std::string::npos);
        CHECK_FALSE(fs::exists(dir.path / "gone"));
        CHECK_FALSE(fs::exists(dir.path / "new/fresh"));
        CHECK(fs::is_directory(dir.path / "new/deeper/out"));
    }
    // A file under the folder's name is refused by name, as every command's output folder.
    const auto file = run_cli("decode --batch caps" + m + "-o m.mask.json", dir.path);
    CHECK(file.exit_code == 2);
    CHECK(file.err.find("is a file; give a folder (created when missing)") != std::string::npos);
}

// PINMASK_TIME_LIMIT: the budget is checked between captures and each run decodes at least its
// first capture, so a budget of 1 us (the smallest accepted; spent before the first check on any
// machine) keeps exactly c1: its files are those of a run without a budget, the others are
// listed as not done, nothing else is written, exit code 3. No wall-clock figure is asserted.
TEST_CASE("decode --batch: a spent time budget keeps the captures finished, lists the others") {
    TempDir dir("cli-decode-batch-time");
    make_captures(dir);
    // Each run in its own folder with the same relative paths (the files record them).
    const auto run_in = [&](const std::string& name, const std::string& extra = "") {
        fs::create_directories(dir.path / name / "out");
        return run_cli(
            "decode --batch ../caps --mask ../m.mask.json --method wiener --nsr 1e-3 "
            "--batch-stats " +
                extra + "-o out",
            dir.path / name);
    };
    const auto free = run_in("free");
    REQUIRE(free.exit_code == 0);
    // A budget that is not spent changes nothing: the same bytes, no "stopped".
    ::setenv("PINMASK_TIME_LIMIT", "1h", 1);
    const auto roomy = run_in("roomy");
    ::setenv("PINMASK_TIME_LIMIT", "1e-6", 1);
    const auto tight = run_in("tight");
    const auto tight_json = run_in("tight-json", "--json ");
    ::unsetenv("PINMASK_TIME_LIMIT");

    INFO(roomy.err);
    REQUIRE(roomy.exit_code == 0);
    for (const std::string name :
         {"batch-summary.json", "c1.tiff", "c2.tiff", "c3.tiff", "c3.tiff.config.json"})
        CHECK(slurp(dir.path / "roomy/out" / name) == slurp(dir.path / "free/out" / name));

    INFO(tight.err);
    REQUIRE(tight.exit_code == 3);
    CHECK(tight.err.find("PINMASK_TIME_LIMIT = 1e-06 s was spent") != std::string::npos);
    CHECK(tight.err.find("stopped after 1 of 3 captures") != std::string::npos);
    CHECK(tight.out.find("decode ../caps/c1.tiff") != std::string::npos);
    CHECK(tight.out.find("caps/c2.tiff") == std::string::npos);
    CHECK(tight.out.find("3 captures (2 not done)") != std::string::npos);
    const fs::path out = dir.path / "tight/out";
    CHECK(file_count(out) == 3 + 1);  // c1's image, config and stats; the summary
    for (const std::string name : {"c1.tiff", "c1.tiff.config.json"})
        CHECK(slurp(out / name) == slurp(dir.path / "free/out" / name));
    CHECK(fs::exists(out / "c1.stats.json"));
    const auto summary = nlohmann::json::parse(slurp(out / "batch-summary.json"));
    const auto full = nlohmann::json::parse(slurp(dir.path / "free/out/batch-summary.json"));
    REQUIRE(summary["captures"].size() == 3);
    CHECK(summary["captures"][0] == full["captures"][0]);
    for (int i = 1; i < 3; ++i) {
        const auto& e = summary["captures"][i];
        CHECK(e["input"] == "../caps/c" + std::to_string(i + 1) + ".tiff");
        CHECK(e["output"].is_null());
        CHECK(e["not_done"].get<std::string>().find("PINMASK_TIME_LIMIT") != std::string::npos);
    }
    CHECK(summary["stopped"]["done"] == 1);
    CHECK(summary["stopped"]["not_done"] == 2);
    CHECK(!full.contains("stopped"));

    // --json prints the same summary before exit code 3.
    INFO(tight_json.err);
    REQUIRE(tight_json.exit_code == 3);
    const auto printed = nlohmann::json::parse(tight_json.out);
    CHECK(printed["stopped"] == summary["stopped"]);
    CHECK(file_count(dir.path / "tight-json/out") == 3 + 1);
}

TEST_CASE("decode --batch: a full-resolution PSF for binned RAW captures is refused, not misread") {
    // A capture alone bins a PSF at twice its size 2 x 2 (core/image/mosaic.hpp); a batch
    // shares one PSF over every capture, so it refuses instead of decoding at the wrong sampling
    // (exit 0 with an estimate of garbage before).
    TempDir dir("cli-decode-batch-raw-psf");
    pinmask::test::DngSpec dng;
    dng.rows = 24;
    dng.cols = 32;
    dng.values.assign(static_cast<std::size_t>(dng.rows) * dng.cols, 100);
    for (std::size_t i = 0; i < dng.values.size(); i += 7) dng.values[i] = 900;
    fs::create_directory(dir.path / "raws");
    pinmask::test::write_dng(dir.path / "raws/a.dng", dng);
    pinmask::Image psf;
    psf.channels.push_back(pinmask::Plane::Zero(dng.rows, dng.cols));
    psf.channels[0](3, 5) = 1.0;
    psf.channels[0](17, 20) = 2.0;
    pinmask::write_image(dir.path / "psf.tiff", psf);  // the sensor's full resolution: 24 x 32
    const auto batch = run_cli("decode --batch raws --psf psf.tiff -o out", dir.path);
    INFO(batch.err);
    CHECK(batch.exit_code == 2);
    CHECK(batch.err.find("one PSF serves every capture of a batch") != std::string::npos);
    CHECK(batch.err.find("32 x 24") != std::string::npos);
    CHECK_FALSE(fs::exists(dir.path / "out"));
    // Alone, the same capture and PSF decode, the PSF binned as the capture was.
    const auto alone = run_cli("decode raws/a.dng --psf psf.tiff -o alone.tiff", dir.path);
    INFO(alone.err);
    CHECK(alone.exit_code == 0);
    CHECK(alone.err.find("2 x 2 blocks summed") != std::string::npos);
}
