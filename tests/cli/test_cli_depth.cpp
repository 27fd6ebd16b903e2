// `pinmask depth` end to end: the loss at 6 m against a direct simulation written for the test,
// the loss growing as u falls, the files of -o DIR, and bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "decode/decoder.hpp"
#include "design/psf.hpp"
#include "design/psf_exact.hpp"
#include "io/mask_json.hpp"
#include "simulate/scenes.hpp"
#include "simulate/simulate.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kPaperMask = std::string(PINMASK_SOURCE_DIR) + "/masks/paper-best/mask.json";

// The same arithmetic in another order (a shift found by direct search, MSE summed directly):
// rounding only.
constexpr double kLossTolDb = 1e-6;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

nlohmann::json depth_json(const std::string& args) {
    const auto r = run_cli("depth --json " + args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

// PSNR (peak 1) of x against the scene after the best cyclic shift, by direct search.
double registered_psnr(const Plane& x, const Plane& scene) {
    const int m = static_cast<int>(x.rows());
    double best = INFINITY;
    for (int dr = 0; dr < m; ++dr) {
        for (int dc = 0; dc < m; ++dc) {
            double sse = 0;
            for (int i = 0; i < m && sse < best; ++i) {
                for (int j = 0; j < m; ++j) {
                    const double e =
                        x(i, j) - scene(((i - dr) % m + m) % m, ((j - dc) % m + m) % m);
                    sse += e * e;
                }
            }
            best = std::min(best, sse);
        }
    }
    return 10.0 * std::log10(1.0 / (best / (double(m) * m)));
}

double wiener_psnr(const Plane& capture, const Plane& psf, const Plane& scene) {
    DecodeOptions d;
    d.wiener.nsr = 0.01;
    return registered_psnr(decode_plane(capture, psf, d).image, scene);
}

}  // namespace

TEST_CASE("depth of the paper mask: the Wiener loss at 6 m equals a direct simulation") {
    const auto j = depth_json(kPaperMask + " --distances 6m --snr inf --scenes letter-R --no-tv");
    REQUIRE(j.size() == 1);
    const double loss = j[0]["wiener_psnr_loss_db"].get<double>();

    // Direct: the exact capture at 6 m on a window of the whole tiled mask plus the scene, its
    // centred period, decoded with the integer PSF; against the cyclic capture decoded the same.
    const Mask m = io::read_mask_file(kPaperMask);
    const Plane psf = mask_psf(m);
    const int p = static_cast<int>(psf.rows());
    const Plane scene = make_scene(scene_from_name("letter-R"), p, p).channels[0];
    ExactPsfOptions eo;
    eo.object_distance_m = 6.0;
    eo.rows = eo.cols = 4 * p;
    const Plane exact = exact_psf(m, eo);
    const int o = (eo.rows - p) / 2;
    const Plane cap = linear_capture(scene, exact).block(o, o, p, p);
    const double direct =
        wiener_psnr(cyclic_capture(scene, psf), psf, scene) - wiener_psnr(cap, psf, scene);
    CHECK(std::fabs(loss - direct) <= kLossTolDb);
    CHECK(loss > 0.0);
}

TEST_CASE("depth: the loss grows as u falls; mismatch and period follow the pitch") {
    // The paper mask's pitch is exactly 8 px near u = 14.5 m; below that the loss must grow.
    const auto j = depth_json(kPaperMask + " --distances 14.5m,6m,3m,2m");
    REQUIRE(j.size() == 4);
    for (std::size_t i = 1; i < j.size(); ++i) {
        INFO("distance " << j[i]["object_distance_m"]);
        CHECK(j[i]["wiener_psnr_loss_db"].get<double>() >
              j[i - 1]["wiener_psnr_loss_db"].get<double>());
        CHECK(j[i]["tv_psnr_loss_db"].get<double>() > j[i - 1]["tv_psnr_loss_db"].get<double>());
        CHECK(j[i]["lsi_mismatch_px"].get<double>() > j[i - 1]["lsi_mismatch_px"].get<double>());
        CHECK(j[i]["period_px"].get<double>() > j[i - 1]["period_px"].get<double>());
    }
    for (const char* key : {"object_distance_m", "pixels_per_cell", "period_px", "lsi_mismatch_px",
                            "wiener_psnr_loss_db", "tv_psnr_loss_db"}) {
        CHECK(j[0].contains(key));
    }
    const auto inf = depth_json(kPaperMask + " --distances inf --no-tv");
    CHECK(inf[0]["object_distance_m"].is_null());
    CHECK(inf[0]["tv_psnr_loss_db"].is_null());
}

TEST_CASE("depth -o DIR writes the plot (SVG + PNG) and the records; bad input exits 2") {
    TempDir dir("depth");
    const auto r = run_cli("depth " + kPaperMask + " --from 3m --to inf --steps 3 --no-tv -o " +
                           dir.path.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(contains(r.out, "Wiener loss dB"));
    for (const char* f : {"depth.svg", "depth.png", "depth.json"}) CHECK(fs::exists(dir / f));
    TempDir empty("depth-bad");
    auto refused = [&](const std::string& args, const std::string& says) {
        const auto b = run_cli("depth " + kPaperMask + " " + args + " -o " + empty.path.string());
        INFO(args << " -> " << b.err);
        CHECK(b.exit_code == 2);
        CHECK(contains(b.err, says));
        CHECK(fs::is_empty(empty.path));
    };
    refused("--distances 10cm", "focal length");
    refused("--from 6m --to 2m", "--to");
    refused("--distances 6m --from 2m --to 3m", "--distances");
    refused("", "--distances");
    refused("--distances 6m --snr loud", "--snr");
    refused("--distances 6m --scenes nope", "nope");
}

TEST_CASE("decode --object-distance refocuses: the PSF for that distance (whole pixels at u)") {
    TempDir dir("refocus");
    const std::string cam =
        "--pixel-pitch 3.45um --sensor 1024x1024 --lens-focal 25mm --sensor-distance 20mm "
        "--object-distance 2m --wavelength 530nm --pinhole 345um";
    const std::string mask = (dir / "m.mask.json");
    REQUIRE(run_cli("generate " + cam + " --seed 2 -o " + mask).exit_code == 0);
    // At 1 m the pitch is 345 um x (1 - 20/25 + 20/1000) / 3.45 um = 22 px exactly (21 at 2 m).
    const std::string cap = (dir / "c.npy");
    REQUIRE(
        run_cli("simulate " + mask + " --geometry exact --object-distance 1m --snr inf -o " + cap)
            .exit_code == 0);
    auto psf_rows = [&](const std::string& extra) {
        const std::string stats = (dir / "s.json");
        const auto r = run_cli("decode " + cap + " --mask " + mask + " -o " + (dir / "d.npy") +
                               " --stats " + stats + extra);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        return nlohmann::json::parse(test::slurp(stats))["psf"]["rows"].get<int>();
    };
    CHECK(psf_rows("") == 16 * 21);
    CHECK(psf_rows(" --object-distance 1m") == 16 * 22);
    const auto bad = run_cli("decode " + cap + " --mask " + mask + " -o " + (dir / "x.npy") +
                             " --object-distance 1cm");
    CHECK(bad.exit_code == 2);
    CHECK(contains(bad.err, "--object-distance"));
    CHECK_FALSE(fs::exists(dir / "x.npy"));
}
