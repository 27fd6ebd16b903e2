// `pinmask score` end to end on two masks written by `pinmask generate` (a small geometry so the
// simulated metrics stay fast: 8 x 8 cells of 4 pixels, a 32 x 32 period).
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli/generated_masks.hpp"
#include "tests/support/cli_run.hpp"

using pinmask::test::run_cli;
using pinmask::test::TempDir;

namespace {

struct Masks : pinmask::test::GeneratedMasks {
    Masks() : GeneratedMasks("score") {}
};

}  // namespace

TEST_CASE("score --json: one row per mask with self-describing keys") {
    Masks m;
    const auto r =
        run_cli("score " + m.a + " " + m.b + " --snr 20,30 --scenes letter-R,natural --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["masks"].size() == 2);
    for (const auto& row : j["masks"]) {
        for (const char* key :
             {"geometry_hash", "peak_autocorrelation", "max_sidelobe", "mean_sidelobe",
              "integrated_sidelobe_level", "peak_to_sidelobe_ratio", "min_abs_pattern_spectrum",
              "spectral_flatness", "open_fraction", "light_gain", "otf_condition_number",
              "analytic_wiener_psnr_db_snr20", "analytic_wiener_psnr_db_snr30",
              "analytic_mmse_psnr_db_snr30", "sim_wiener_psnr_db_snr20", "sim_wiener_ssim_snr30",
              "per_scene"}) {
            INFO(key);
            CHECK(row.contains(key));
        }
        CHECK(row["peak_autocorrelation"] == 5);
        CHECK(!row.contains("sim_tv_psnr_db_snr20"));  // not requested, not run
        CHECK(row["per_scene"].contains("letter-R"));
        // More SNR, better expected reconstruction.
        CHECK(row["analytic_wiener_psnr_db_snr30"].get<double>() >
              row["analytic_wiener_psnr_db_snr20"].get<double>());
    }
    CHECK(!j.contains("explain"));
}

TEST_CASE("score prints a table, and --explain names what was skipped") {
    Masks m;
    const auto r = run_cli("score " + m.a + " " + m.b + " --metrics sidelobes --explain");
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("a.mask.json") != std::string::npos);
    CHECK(r.out.find("b.mask.json") != std::string::npos);
    CHECK(r.err.find("tv: skipped") != std::string::npos);
    CHECK(r.err.find("wiener: skipped") != std::string::npos);
    const auto j = run_cli("score " + m.a + " --metrics sidelobes,spectrum --explain --json");
    REQUIRE(j.exit_code == 0);
    const auto parsed = nlohmann::json::parse(j.out);
    REQUIRE(parsed.contains("explain"));
    CHECK(parsed["explain"].dump().find("analytic: skipped") != std::string::npos);
    CHECK(!parsed["masks"][0].contains("sim_wiener_psnr_db_snr30"));
}

TEST_CASE("score: TV runs only when asked, with tuned weights") {
    Masks m;
    const auto r = run_cli("score " + m.a +
                           " --metrics tv,wiener --snr 25 --scenes checker --nsr tuned "
                           "--tv-iters 30 --json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto row = nlohmann::json::parse(r.out)["masks"][0];
    CHECK(row.contains("sim_tv_psnr_db_snr25"));
    CHECK(row.contains("sim_wiener_nsr_snr25"));
    CHECK(!row.contains("max_sidelobe"));
}

TEST_CASE("score: bad input is exit 2 with a message naming the flag") {
    Masks m;
    auto r = run_cli("score " + m.a + " --metrics sidelobes,bogus");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--metrics") != std::string::npos);
    r = run_cli("score " + m.a + " --nsr 0");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--nsr") != std::string::npos);
    r = run_cli("score " + m.a + " --scenes no-such-file.png");
    CHECK(r.exit_code == 2);
    r = run_cli("score " + (m.dir / "missing.mask.json"));
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
}

TEST_CASE("score --photons: the photon model's levels as columns, sensor flags applied") {
    Masks m;
    const std::string base = "score " + m.a + " --metrics analytic,wiener --nsr tuned --json ";
    const auto r = run_cli(base + "--photons 10,1000");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const auto& row = j["masks"][0];
    for (const char* key : {"analytic_wiener_psnr_db_ph10", "analytic_wiener_psnr_db_ph1000",
                            "sim_wiener_psnr_db_ph10", "sim_wiener_psnr_db_ph1000"})
        CHECK_MESSAGE(row.contains(key), key);
    CHECK(!row.contains("analytic_wiener_psnr_db_snr30"));
    // More light, less shot noise: higher PSNR, analytic and simulated.
    CHECK(row["analytic_wiener_psnr_db_ph1000"].get<double>() >
          row["analytic_wiener_psnr_db_ph10"].get<double>());
    CHECK(row["sim_wiener_psnr_db_ph1000"].get<double>() >
          row["sim_wiener_psnr_db_ph10"].get<double>());
    const auto& noise = j["settings"]["noise"];
    REQUIRE(noise.size() == 2);
    CHECK(noise[0]["kind"] == "photon");
    CHECK(noise[0]["photons_per_pinhole"] == 10.0);
    CHECK(noise[0]["key"] == "ph10");

    // Read noise costs PSNR at a low light level.
    const auto noisy = run_cli(base + "--photons 10 --read-noise 5");
    REQUIRE(noisy.exit_code == 0);
    const auto jn = nlohmann::json::parse(noisy.out);
    CHECK(jn["masks"][0]["analytic_wiener_psnr_db_ph10"].get<double>() <
          row["analytic_wiener_psnr_db_ph10"].get<double>());
    CHECK(jn["settings"]["noise"][0]["read_noise_e"] == 5.0);

    // Sensor flags need the photon model; the two noise models exclude each other.
    auto bad = run_cli("score " + m.a + " --read-noise 5");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--read-noise") != std::string::npos);
    bad = run_cli("score " + m.a + " --photons 10 --snr 30");
    CHECK(bad.exit_code == 2);
    bad = run_cli("score " + m.a + " --photons -5");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("photons") != std::string::npos);
    bad = run_cli("score " + m.a + " --photons 10 --bits 8");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--full-well") != std::string::npos);
}
