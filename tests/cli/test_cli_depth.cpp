// `pinmask depth` end to end: the loss at 6 m against a direct simulation written for the test
// (Gaussian-free and under the photon model), the tuned NSR equal to score's, the loss growing as
// u falls, the files of -o DIR (created when missing), progress lines on a pipe, and bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "decode/capture/decoder.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "io/mask_json.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"
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

// What the sensor records of `scene` at u metres, as the test computes it: the centred period of
// the linear capture through the exact PSF of the whole tiled mask on a window of four periods.
Plane exact_period_capture(const Mask& m, const Plane& scene, double u_m) {
    const int p = static_cast<int>(scene.rows());
    ExactPsfOptions eo;
    eo.object_distance_m = u_m;
    eo.rows = eo.cols = 4 * p;
    const int o = (eo.rows - p) / 2;
    return linear_capture(scene, exact_psf(m, eo)).block(o, o, p, p);
}

double wiener_psnr(const Plane& capture, const Plane& psf, const Plane& scene, double nsr = 0.01) {
    DecodeOptions d;
    d.wiener.nsr = nsr;
    return registered_psnr(decode_plane(capture, psf, d).image, scene);
}

}  // namespace

TEST_CASE("depth of the paper mask: the Wiener loss at 6 m equals a direct simulation") {
    const auto j =
        depth_json(kPaperMask + " --distances 6m --snr inf --scenes letter-R --no-tv --nsr 0.01");
    REQUIRE(j.size() == 1);
    const double loss = j[0]["wiener_psnr_loss_db"].get<double>();

    // Direct: the exact capture at 6 m on a window of the whole tiled mask plus the scene, its
    // centred period, decoded with the integer PSF; against the cyclic capture decoded the same.
    const Mask m = io::read_mask_file(kPaperMask);
    const Plane psf = mask_psf(m);
    const int p = static_cast<int>(psf.rows());
    const Plane scene = make_scene(scene_from_name("letter-R"), p, p).channels[0];
    const Plane cap = exact_period_capture(m, scene, 6.0);
    const double direct =
        wiener_psnr(cyclic_capture(scene, psf), psf, scene) - wiener_psnr(cap, psf, scene);
    CHECK(std::fabs(loss - direct) <= kLossTolDb);
    CHECK(loss > 0.0);
}

TEST_CASE("depth under the photon model: the Wiener loss equals a direct simulation") {
    // 20 e- per pinhole, 6 e- read noise, NSR fixed (the tuned one is checked below); the test's
    // exact capture is the centred period of the full linear capture on a 4-period window,
    // noised by the photon model with the generator depth documents for scene 0 of seed 7.
    const auto j = depth_json(kPaperMask +
                              " --distances 3m --photons 20 --read-noise 6 --scenes natural "
                              "--no-tv --nsr 0.003 --seed 7");
    REQUIRE(j.size() == 1);
    CHECK(j[0]["wiener_nsr"].get<double>() == 0.003);
    const Mask m = io::read_mask_file(kPaperMask);
    const Plane psf = mask_psf(m);
    const int p = static_cast<int>(psf.rows());
    const Plane scene = make_scene(scene_from_name("natural"), p, p).channels[0];
    const Plane clean = exact_period_capture(m, scene, 3.0);
    NoiseModel photon;
    photon.kind = NoiseKind::kPhoton;
    photon.photons_per_pinhole = 20;
    photon.read_noise_e = 6;
    const int k = static_cast<int>(m.pattern.pinholes.size()), cells = m.pattern.n * m.pattern.n;
    auto noised = [&](const Plane& c) {
        std::mt19937_64 rng(7ULL * 1000003ULL);
        return add_noise(c, photon, k, cells, rng);
    };
    const double direct = wiener_psnr(noised(cyclic_capture(scene, psf)), psf, scene, 0.003) -
                          wiener_psnr(noised(clean), psf, scene, 0.003);
    CHECK(j[0]["wiener_psnr_loss_db"].get<double>() == doctest::Approx(direct).epsilon(1e-9));
}

TEST_CASE("depth tunes the Wiener NSR as score does: the same NSR for the same scenes and noise") {
    const auto j =
        depth_json(kPaperMask + " --distances 6m,3m --photons 20 --read-noise 6 --no-tv --seed 1");
    const auto r = run_cli("score " + kPaperMask +
                           " --photons 20 --read-noise 6 --nsr tuned --scenes letter-R,natural "
                           "--metrics wiener --seed 1 --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const double score_nsr =
        nlohmann::json::parse(r.out)["masks"][0]["sim_wiener_nsr_ph20"].get<double>();
    CHECK(score_nsr != 0.01);
    for (const auto& rec : j) CHECK(rec["wiener_nsr"].get<double>() == score_nsr);
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
    CHECK(contains(r.out, "Wiener NSR"));
    for (const char* f : {"depth.svg", "depth.png", "depth.json"}) CHECK(fs::exists(dir / f));
    // A folder that does not exist yet is created (with its parents).
    const fs::path fresh = dir.path / "new" / "depth";
    REQUIRE(
        run_cli("depth " + kPaperMask + " --distances 6m --no-tv -o " + fresh.string()).exit_code ==
        0);
    CHECK(fs::exists(fresh / "depth.json"));
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
    refused("--distances 6m --read-noise 6", "give --photons too");
    refused("--distances 6m --photons 20,40", "one noise level");
    refused("--distances 6m --photons -1", "--photons");
    refused("--distances 6m --nsr 0", "--nsr");
    // An option the command lacks is named in command-line order, with its value.
    refused("--distances 6m --brightness 20", "does not take the option(s) --brightness");
    refused("--distances 6m --brightness 20", "no place for the value(s) 20");
}

TEST_CASE("depth with stderr on a pipe prints plain progress lines: the set-up phase, 100 %") {
    TempDir dir("depth-pipe");
    const fs::path err = dir.path / "err.txt";
    const std::string cmd = std::string(PINMASK_EXE) + " depth " + kPaperMask +
                            " --distances 6m,3m,2m --no-tv 2>&1 >/dev/null </dev/null | cat > " +
                            err.string();
    REQUIRE(std::system(cmd.c_str()) == 0);
    const std::string text = test::slurp(err);
    INFO(text);
    CHECK(contains(text, "pinmask depth: tuning the Wiener NSR and decoding the reference"));
    CHECK(contains(text, "pinmask depth: 100% 3/3 distances\n"));
    CHECK_FALSE(contains(text, "\r"));  // no bar redrawn in place
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
