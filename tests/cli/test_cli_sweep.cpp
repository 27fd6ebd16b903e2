// `pinmask sweep` end to end: the outputs of a small grid, byte-identical on a rerun,
// under `mpirun -n 2` and `mpirun -n 3 --oversubscribe` (dynamic work queue; files independent
// of the rank count and of scheduling), and bad sweep files refused with exit 2 naming the key
// before any search runs (no output folder created).
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/sweep_config.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::CliResult;
using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// 2 x 2 x 2 points on an 8 x 8 grid, 60 evaluations each: a few seconds in all.
constexpr const char* kSweep = R"({"format": "pinmask-sweep", "version": 1,
  "base": {"grid": 8, "tiles": 1, "pixels_per_cell": 4, "evaluations_per_chain": 60,
           "top": 2, "rerank_scenes": [], "prior": {"family": "natural", "scenes": 2},
           "noise": {"model": "photon", "photons_per_pinhole": 100}},
  "grid": {"holes": [3, 5], "noise.photons_per_pinhole": [10, 1000], "seed": [1, 2]}})";

// Runs the executable under mpirun with n ranks (as root in CI containers; oversubscribed so
// 3 ranks run on 2 cores).
CliResult run_mpi(int ranks, const std::string& args) {
    const auto dir = fs::temp_directory_path();
    const std::string tag = std::to_string(::getpid()) + "-mpi-" + std::to_string(ranks);
    const fs::path out = dir / ("pinmask-cli-" + tag + ".out");
    const fs::path err = dir / ("pinmask-cli-" + tag + ".err");
    // Under sanitizers: no leak checking in the MPI processes (Open MPI's dlopen'ed components
    // keep state LeakSanitizer cannot attribute; see tests/CMakeLists.txt).
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string env = std::getenv("PINMASK_SANITIZED") && asan
                                ? "ASAN_OPTIONS='" + std::string(asan) + ":detect_leaks=0' "
                                : "";
    const std::string cmd = env + "mpirun --allow-run-as-root --oversubscribe -n " +
                            std::to_string(ranks) + " " + PINMASK_EXE + " " + args + " >" +
                            out.string() + " 2>" + err.string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

// Every file under a (relative path -> bytes).
std::map<std::string, std::string> files_under(const fs::path& root) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file()) out[fs::relative(e.path(), root).string()] = slurp(e.path());
    return out;
}

}  // namespace

TEST_CASE("sweep: table, masks, plots; a rerun and 2 or 3 MPI ranks give identical files") {
    TempDir dir("sweep");
    std::ofstream(dir / "sweep.json") << kSweep;
    const auto r = run_cli("sweep " + (dir / "sweep.json") + " --quiet --json -o " + (dir / "one"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["points"] == 8);
    REQUIRE(j["rows"].size() == 8);
    const auto one = files_under(dir.path / "one");
    for (const char* f :
         {"sweep.csv", "sweep.md", "sweep.config.json", "psnr-vs-holes.svg", "psnr-vs-holes.png",
          "psnr-vs-light.svg", "psnr-vs-light.png", "points/point-0000.mask.json",
          "points/point-0007.mask.json", "points/point-0007.search.config.json"})
        CHECK_MESSAGE(one.count(f) == 1, f);
    CHECK(one.count("psnr-vs-pinhole-size.svg") == 0);  // the pinhole size does not vary
    // One CSV row per point, in point order, with the point's values and its best mask.
    const std::string& csv = one.at("sweep.csv");
    CHECK(csv.rfind("point,holes,noise.photons_per_pinhole,seed,K,pinhole_m,", 0) == 0);
    CHECK(csv.find("\n7,5,1000,2,5,") != std::string::npos);
    for (int i = 0; i < 8; ++i) {
        const auto mask =
            nlohmann::json::parse(one.at("points/point-000" + std::to_string(i) + ".mask.json"));
        CHECK(mask["pattern"]["pinholes"].size() == (i < 4 ? 3u : 5u));
        CHECK(mask["provenance"]["seed"] == (i % 2 == 0 ? 1 : 2));
        CHECK(j["rows"][i]["geometry_hash"].get<std::string>().size() == 16);
    }
    // More light, better analytic PSNR (same K, same seed).
    CHECK(j["rows"][2]["analytic_wiener_psnr_db"].get<double>() >
          j["rows"][0]["analytic_wiener_psnr_db"].get<double>());
    // A point's search.config.json repeats it with `pinmask search`: the same best mask.
    const auto s = run_cli("search --config " + (dir / "one/points/point-0005.search.config.json") +
                           " --quiet --top 1 -o " + (dir / "repeat"));
    REQUIRE(s.exit_code == 0);
    CHECK(nlohmann::json::parse(slurp(dir.path / "repeat" / "rank-1.mask.json"))["pattern"] ==
          nlohmann::json::parse(one.at("points/point-0005.mask.json"))["pattern"]);

    const auto again = run_cli("sweep " + (dir / "sweep.json") + " --quiet -o " + (dir / "two"));
    REQUIRE(again.exit_code == 0);
    CHECK(files_under(dir.path / "two") == one);
    for (int ranks : {1, 2, 3}) {
        CAPTURE(ranks);
        const std::string out = "mpi" + std::to_string(ranks);
        const auto m =
            run_mpi(ranks, "sweep " + (dir / "sweep.json") + " --quiet -o " + (dir / out));
        INFO(m.err);
        REQUIRE(m.exit_code == 0);
        CHECK(files_under(dir.path / out) == one);
    }
}

TEST_CASE("sweep: a bad sweep file is exit 2 naming the key, before any work, on every rank") {
    TempDir dir("sweep-bad");
    const std::string head = R"({"format": "pinmask-sweep", "version": 1, "base": {"grid": 8,
        "evaluations_per_chain": 20, "noise": {"model": "photon", "photons_per_pinhole": 10}}, )";
    const std::pair<const char*, const char*> cases[] = {
        {R"("grid": {"holez": [3, 4]}})", "holez: unknown key"},
        {R"("grid": {}})", "grid: empty grid"},
        {R"("grid": {"noise.snr_db": [10, 20]}})", "noise.snr_db: belongs to the gaussian model"},
        {R"("grid": {"holes": [3, 400]}})", "holes"},
    };
    int i = 0;
    for (const auto& [body, key] : cases) {
        const std::string file = dir / ("bad" + std::to_string(i++) + ".json");
        std::ofstream(file) << head << body;
        for (int ranks : {0, 2}) {
            CAPTURE(file);
            CAPTURE(ranks);
            const std::string args = "sweep " + file + " --quiet -o " + (dir / "out");
            const auto r = ranks == 0 ? run_cli(args) : run_mpi(ranks, args);
            CHECK(r.exit_code == 2);
            CHECK(r.err.find(key) != std::string::npos);
            CHECK(!fs::exists(dir.path / "out"));
        }
    }
}

TEST_CASE("sweep --help: the example sweep file it teaches is a valid sweep file") {
    const auto r = run_cli("sweep --help");
    REQUIRE(r.exit_code == 0);
    // The example runs from the line after "Example:" to the line before "or \"points\"".
    const auto from = r.out.find("Example:\n");
    const auto to = r.out.find("or \"points\"");
    REQUIRE(from != std::string::npos);
    REQUIRE(to != std::string::npos);
    const std::string example = r.out.substr(from + 9, to - from - 9);
    const pinmask::io::SweepConfig c = pinmask::io::parse_sweep_config(example);
    CHECK(c.points.size() == 9);
    CHECK(c.keys == std::vector<std::string>{"holes", "noise.photons_per_pinhole"});
}
