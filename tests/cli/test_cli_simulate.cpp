// `pinmask simulate` end to end on the paper-family mask written by `pinmask generate` (16 x 16
// cells of 8 pixels: a 128 x 128 period).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/image/image_io.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// z-score bound of the statistical check: a correct sampler fails with probability ~6e-7.
constexpr double kZ = 5.0;
// float32 files: a capture value near 1 is stored to 2^-24 relative.
constexpr double kFloat32Tol = 1e-6;

struct PaperMask {
    TempDir dir{"simulate"};
    std::string mask;
    PaperMask() {
        mask = dir / "paper.mask.json";
        REQUIRE(run_cli("generate --family paper --seed 1 -o " + mask).exit_code == 0);
    }
};

pinmask::Plane read_plane(const std::string& path) {
    return pinmask::read_image(path).image.channels.at(0);
}

}  // namespace

TEST_CASE("simulate --help teaches the model, the flags and the files") {
    const auto r = run_cli("simulate --help");
    REQUIRE(r.exit_code == 0);
    for (const char* s :
         {"exact for the cyclic model", "--photons", "--read-noise", "--full-well", "--bits",
          "--optical-density", "--dark-frame", "--full-sensor", ".config.json", "Examples:"}) {
        INFO(s);
        CHECK(r.out.find(s) != std::string::npos);
    }
}

TEST_CASE("simulate: capture + resolved configuration; --explain names the skipped stages") {
    PaperMask m;
    const std::string out = m.dir / "cap.tiff";
    const auto r =
        run_cli("simulate " + m.mask + " --scene usaf --snr inf -o " + out + " --explain");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("noise skipped: --snr inf") != std::string::npos);
    CHECK(r.err.find("full-sensor tiling skipped: --full-sensor not given") != std::string::npos);
    CHECK(r.err.find("dark frame skipped") != std::string::npos);
    const auto cfg = nlohmann::json::parse(slurp(out + ".config.json"));
    CHECK(cfg["format"] == "pinmask-simulate-config");
    CHECK(cfg["noise"]["kind"] == "none");
    CHECK(cfg["scene"]["name"] == "usaf");
    CHECK(cfg["psf"]["period_px"] == 128);
    const pinmask::LoadedImage img = pinmask::read_image(out);
    CHECK(img.format == pinmask::SampleFormat::kFloat32);
    CHECK(img.image.rows() == 128);
    CHECK(img.image.cols() == 128);
}

TEST_CASE("simulate is deterministic per seed, in every output format") {
    PaperMask m;
    for (const char* ext : {".tiff", ".png", ".npy"}) {
        const std::string a = m.dir / (std::string("a") + ext),
                          b = m.dir / (std::string("b") + ext),
                          c = m.dir / (std::string("c") + ext);
        const std::string common = "simulate " + m.mask + " --scene natural --snr 25 ";
        REQUIRE(run_cli(common + "--seed 4 -o " + a).exit_code == 0);
        REQUIRE(run_cli(common + "--seed 4 -o " + b).exit_code == 0);
        REQUIRE(run_cli(common + "--seed 5 -o " + c).exit_code == 0);
        CHECK(slurp(a) == slurp(b));
        CHECK(slurp(a) != slurp(c));
    }
}

TEST_CASE("full sensor: the centred crop is the one-period capture; decode agrees") {
    PaperMask m;
    const std::string period = m.dir / "p.tiff", full = m.dir / "f.tiff", psf = m.dir / "psf.tiff";
    REQUIRE(run_cli("simulate " + m.mask + " --scene letter-R --snr inf -o " + period).exit_code ==
            0);
    const auto r = run_cli("simulate " + m.mask +
                           " --scene letter-R --snr inf --full-sensor --json -o " + full);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["rows"] == 480);
    CHECK(j["cols"] == 720);
    const pinmask::Plane p = read_plane(period), f = read_plane(full);
    // The period sits at ((480 - 128) / 2, (720 - 128) / 2) and repeats with period 128.
    CHECK((f.block(176, 296, 128, 128) == p).all());
    CHECK((f.block(176 - 128, 296 + 128, 128, 128) == p).all());
    // The decoder's default centred crop takes the same period.
    REQUIRE(run_cli("psf " + m.mask + " -o " + psf).exit_code == 0);
    const std::string d1 = m.dir / "d1.npy", d2 = m.dir / "d2.npy";
    REQUIRE(run_cli("decode " + period + " --psf " + psf + " -o " + d1).exit_code == 0);
    REQUIRE(run_cli("decode " + full + " --psf " + psf + " -o " + d2).exit_code == 0);
    CHECK((read_plane(d1) - read_plane(d2)).abs().maxCoeff() <= kFloat32Tol);
}

TEST_CASE("photon model with leak and dark current: the dark frame's mean is the background") {
    PaperMask m;
    const std::string cap = m.dir / "cap.tiff", dark = m.dir / "dark.tiff";
    const auto r = run_cli("simulate " + m.mask +
                           " --scene natural --photons 100 --read-noise 2 --dark-current 6 "
                           "--optical-density 1 --dark-frame " +
                           dark + " --json -o " + cap);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const double background = j["background_per_channel"][0].get<double>();
    const pinmask::Plane d = read_plane(dark);
    // Electrons per normalised unit: 100 photons per pinhole x 20 pinholes.
    const double scale = 100.0 * 20.0;
    const double sd = std::sqrt(background * scale + 2.0 * 2.0) / scale;
    CHECK(background > 6.0 / scale);  // the leak adds to the dark current
    CHECK(std::fabs(d.mean() - background) < kZ * sd / std::sqrt(double(d.size())));
    const auto cfg = nlohmann::json::parse(slurp(cap + ".config.json"));
    CHECK(cfg["noise"]["film_optical_density"] == 1.0);
    CHECK(cfg["outputs"]["dark_frame"] == dark);
}

TEST_CASE("simulate refuses bad requests with exit 2 and writes nothing") {
    PaperMask m;
    const std::string out = m.dir / "x.tiff";
    for (const std::string& args : {
             std::string(" --snr 30 --dark-frame ") + (m.dir / "d.tiff"),  // no dark signal
             std::string(" --read-noise 3"),                               // photon-only flag
             std::string(" --photons 100 --bits 12"),                      // ADC without full well
             std::string(" --photons -1"),                                 // not physical
             std::string(" --snr loud"),                                   // not a number
             std::string(" --scene no-such-scene.png"),                    // missing scene file
             std::string(" --sensor 256x256"),                             // needs --full-sensor
         }) {
        INFO(args);
        const auto r = run_cli("simulate " + m.mask + args + " -o " + out);
        CHECK(r.exit_code == 2);
        CHECK(!fs::exists(out));
        CHECK(!fs::exists(out + ".config.json"));
        CHECK(!fs::exists(m.dir / "d.tiff"));
    }
    CHECK(run_cli("simulate " + m.mask + " -o " + (m.dir / "x.bmp")).exit_code == 2);
    CHECK(run_cli("simulate " + (m.dir / "missing.mask.json") + " -o " + out).exit_code == 2);
}

TEST_CASE("simulate --precision: double = the default bytes (128 px < 256), single within float") {
    PaperMask m;
    const std::string base = m.dir / "base.tiff", dbl = m.dir / "dbl.tiff",
                      sgl = m.dir / "sgl.tiff";
    const std::string args = "simulate " + m.mask + " --scene usaf --snr 30 --seed 4 ";
    REQUIRE(run_cli(args + "-o " + base).exit_code == 0);
    REQUIRE(run_cli(args + "--precision double -o " + dbl).exit_code == 0);
    CHECK(slurp(base) == slurp(dbl));
    auto cfg_base = nlohmann::json::parse(slurp(base + ".config.json"));
    auto cfg_dbl = nlohmann::json::parse(slurp(dbl + ".config.json"));
    for (const char* k : {"outputs", "explain"}) {  // the file names and the flag as typed
        cfg_base.erase(k);
        cfg_dbl.erase(k);
    }
    CHECK(cfg_base == cfg_dbl);
    const auto r = run_cli(args + "--precision single --explain -o " + sgl);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("convolution in float32") != std::string::npos);
    CHECK(nlohmann::json::parse(slurp(sgl + ".config.json"))["precision"] == "single");
    CHECK(nlohmann::json::parse(slurp(dbl + ".config.json"))["precision"] == "double");
    // Measured FFT plans may differ between thread counts, so the count a capture used is recorded.
    const std::string one = m.dir / "one.tiff";
    REQUIRE(run_cli(args + "--threads 1 -o " + one).exit_code == 0);
    CHECK(nlohmann::json::parse(slurp(one + ".config.json"))["threads"] == 1);
    CHECK(slurp(one) == slurp(base));  // estimated plans in tests: the same bytes
    // The float32 convolution moves each value by float rounding of the capture's scale
    // (tests/optimize/simulate/test_simulate_precision.cpp); the file stores float32 either way.
    const pinmask::Plane a = read_plane(sgl), b = read_plane(dbl);
    CHECK(std::sqrt((a - b).square().sum() / b.square().sum()) <= 5e-6);
    const auto bad = run_cli(args + "--precision half -o " + (m.dir / "bad.tiff"));
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--precision") != std::string::npos);
    CHECK_FALSE(fs::exists(m.dir / "bad.tiff"));
}
