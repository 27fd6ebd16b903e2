// The robust design's decoder from the command line: `decode --nsr-map`, `score
// --robust-decoder DIR`, and the whole loop at 50 dB on the paper camera: score writes the
// expected fabricated PSF and the per-frequency NSR, decode applies them to a fabricated capture,
// and the PSNR is the library's fabricated_filter_quality figure for that same capture (the
// robust filter applied by the library's own FFTs, a second code path).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "core/image/image_io.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/decode_request.hpp"
#include "design/optics/camera.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/robust_wiener.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"
#include "tests/research/fabricated_sample.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/random_pattern.hpp"

using pinmask::test::run_cli;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace pinmask {
namespace {

// One float32 rounding of the CLI's .npy output, relative to the largest magnitude.
constexpr double kFloat32Output = 1.0 / (1 << 23);
// The loop's PSNR against the library's figure (float32 output rounding only: ~1e-8 dB).
constexpr double kLoopPsnrToleranceDb = 1e-6;
// The same closed form computed in another run (relative to the largest value).
constexpr double kRoundingTolerance = 1e-12;

Plane read_plane(const fs::path& p) { return read_image(p).image.channels.at(0); }

void write_plane(const fs::path& p, const Plane& x) {
    write_npy(p, Image(x), SampleFormat::kFloat64);
}

}  // namespace

TEST_CASE("decode --nsr-map decodes as the library with the same map") {
    TempDir dir{"nsrmap"};
    const Mask mask = test::random_paper_mask(8, 6, 3);
    const std::string mask_path = dir / "m.mask.json";
    io::write_mask_file(mask_path, mask);
    const int m = 64;
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    Plane capture(m, m), nsr(m, m);
    for (Eigen::Index i = 0; i < capture.size(); ++i) capture.data()[i] = uniform(rng);
    for (Eigen::Index i = 0; i < nsr.size(); ++i) nsr.data()[i] = 1e-3 * (1.0 + 9 * uniform(rng));
    write_plane(dir / "c.npy", capture);
    write_plane(dir / "nsr.npy", nsr);
    const auto r =
        run_cli("decode " + (dir / "c.npy") + " --mask " + mask_path + " --nsr-map " +
                (dir / "nsr.npy") + " -o " + (dir / "x.npy") + " --stats " + (dir / "s.json"));
    REQUIRE(r.exit_code == 0);
    const Plane x = read_plane(dir / "x.npy");

    // The library: the same pipeline with the map in DecodeOptions.
    CaptureDecodeInputs in;
    in.capture = Image(capture);
    in.psf = Image(mask_psf(mask));
    CaptureDecodeOptions o;
    o.decode.wiener.nsr_per_frequency = nsr;
    const Plane lib = decode_capture(in, o).estimate.channels.at(0);
    const double scale = lib.abs().maxCoeff();
    CHECK((x - lib).abs().maxCoeff() <= kFloat32Output * scale);
    // The map is read: the scalar --nsr default decodes differently.
    CaptureDecodeOptions scalar;
    const Plane lib_scalar = decode_capture(in, scalar).estimate.channels.at(0);
    CHECK((x - lib_scalar).abs().maxCoeff() > 1e3 * kFloat32Output * scale);
    const nlohmann::json s = nlohmann::json::parse(test::slurp(dir / "s.json"));
    CHECK(s["nsr_map"]["rows"] == m);
    CHECK(s["config"]["nsr_map"] == (dir / "nsr.npy"));
}

TEST_CASE("hostile --nsr-map inputs exit 2 naming the flag, with no output") {
    TempDir dir{"nsrmapbad"};
    const std::string mask_path = dir / "m.mask.json";
    io::write_mask_file(mask_path, test::random_paper_mask(8, 6, 3));
    const int m = 64;
    write_plane(dir / "c.npy", Plane::Constant(m, m, 0.5));
    write_plane(dir / "ok.npy", Plane::Constant(m, m, 0.01));
    write_plane(dir / "small.npy", Plane::Constant(m - 1, m, 0.01));
    Plane neg = Plane::Constant(m, m, 0.01);
    neg(3, 4) = -1e-9;
    write_plane(dir / "neg.npy", neg);
    Plane nan = Plane::Constant(m, m, 0.01);
    nan(1, 2) = std::nan("");
    write_plane(dir / "nan.npy", nan);
    Image rgb(Plane::Constant(m, m, 0.01));
    rgb.channels.push_back(rgb.channels.front());
    rgb.channels.push_back(rgb.channels.front());
    write_npy(dir / "rgb.npy", rgb, SampleFormat::kFloat64);
    write_png(dir / "int.png", Image(Plane::Constant(m, m, 0.5)), 8);
    const std::string base = "decode " + (dir / "c.npy") + " --mask " + mask_path + " -o " +
                             (dir / "x.npy") + " --nsr-map " + (dir.path.string() + "/");
    const std::pair<std::string, std::string> bad[] = {
        {"small.npy", "working size 64 x 64"},
        {"neg.npy", "negative"},
        {"nan.npy", "finite"},
        {"rgb.npy", "one channel"},
        {"missing.npy", "missing.npy"},
        {"int.png", "floating-point"},
        {"ok.npy --nsr 0.1", "conflicts with --nsr-map"},
        {"ok.npy --method tv", "only by wiener"},
        {"ok.npy --downsample 1", "working size 32 x 32"},
    };
    for (const auto& [args, says] : bad) {
        const std::string a = args, s = says;
        CAPTURE(a);
        const auto r = run_cli(base + a);
        CAPTURE(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("--nsr") != std::string::npos);
        CHECK(r.err.find(s) != std::string::npos);
        CHECK(!fs::exists(dir / "x.npy"));
    }
}

TEST_CASE("score --robust-decoder: refusals and the files it writes") {
    TempDir dir{"robustdec"};
    const Mask mask = test::random_paper_mask(8, 6, 3);
    const std::string a = dir / "a.mask.json";
    io::write_mask_file(a, mask);
    const std::string base = "score " + a + " --metrics analytic --robust size=44um,jitter=2um ";
    const std::pair<std::string, std::string> bad[] = {
        {"--snr 30,40 --robust-decoder " + (dir / "d"), "one noise level"},
        {"--snr 30 --robust-decoder ''", "folder name"},
        {"--snr 30 --robust-decoder " + a, "not a folder"},
    };
    for (const auto& [args, says] : bad) {
        const std::string x = args, s = says;
        CAPTURE(x);
        const auto r = run_cli(base + x);
        CAPTURE(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find("--robust-decoder") != std::string::npos);
        CHECK(r.err.find(s) != std::string::npos);
        CHECK(!fs::exists(dir / "d"));
    }
    auto r = run_cli("score " + a + " " + a + " --snr 30 --robust size=44um --robust-decoder " +
                     (dir / "d"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("exactly one mask") != std::string::npos);
    r = run_cli("score " + a + " --snr 30 --robust-decoder " + (dir / "d"));
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--robust") != std::string::npos);
    CHECK(!fs::exists(dir / "d"));

    // Written: the model's inputs, exactly (float64 .npy), the PSF also as float32 TIFF.
    r = run_cli(base + "--snr 30 --robust-decoder " + (dir / "d"));
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("--nsr-map " + (dir.path / "d" / "robust-nsr.npy").string()) !=
          std::string::npos);
    NoiseModel noise;
    noise.snr_db = 30.0;
    FabricationErrors e;
    e.size_bias_m = 44e-6;
    e.jitter_m = 2e-6;
    const int m = 64;
    const RobustWienerModel model(mask, e, make_scene_prior(parse_prior_spec("natural"), m), noise);
    const RobustDecoderInputs in = model.robust_decoder_inputs(pattern_spectrum(mask.pattern));
    CHECK((read_plane(dir.path / "d" / "robust-psf.npy") - in.psf).abs().maxCoeff() == 0.0);
    CHECK((read_plane(dir.path / "d" / "robust-nsr.npy") - in.nsr).abs().maxCoeff() == 0.0);
    CHECK((read_plane(dir.path / "d" / "robust-psf.tiff") - in.psf).abs().maxCoeff() <=
          kFloat32Output * in.psf.maxCoeff());
    CHECK(fs::exists(dir.path / "d" / "robust-psf.json"));
    // Same inputs, same bytes.
    const std::string first = test::slurp(dir.path / "d" / "robust-nsr.npy");
    REQUIRE(run_cli(base + "--snr 30 --robust-decoder " + (dir / "d")).exit_code == 0);
    CHECK(test::slurp(dir.path / "d" / "robust-nsr.npy") == first);
}

TEST_CASE("the robust decoder loop at 50 dB on the paper camera: CLI PSNR = library figure") {
    // The library test's setting (tests/optimize/search/test_robust_search.cpp): paper camera, 16 x
    // 16 cells of 8 px, 20 pinholes, +-10 % side and 2 um jitter, 50 dB, held-out natural scene.
    TempDir dir{"robustloop"};
    const Mask mask = test::random_paper_mask(16, 20, 5);
    const std::string mask_path = dir / "r.mask.json";
    io::write_mask_file(mask_path, mask);
    const int m = 128;
    FabricationErrors e;
    e.size_bias_m = 44e-6;
    e.jitter_m = 2e-6;
    NoiseModel noise;
    noise.snr_db = 50.0;
    const std::uint64_t seed = 11;
    SceneSpec spec;
    spec.kind = SceneKind::kNatural;
    spec.seed = 7001;
    const Plane truth = make_scene(spec, m, m).channels.at(0);

    // The fabricated capture of fabricated_filter_quality's draw 0 (its draw and noise seeds).
    const FabricationSampler sampler(mask, e);
    std::seed_seq psf_seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                          0u};
    std::mt19937_64 psf_rng(psf_seq);
    const Plane fabricated = sampler.draw(psf_rng);
    std::seed_seq noise_seq{static_cast<std::uint32_t>(seed), 0u, 0u, 0u, 7u};
    std::mt19937_64 noise_rng(noise_seq);
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const Plane capture = add_noise(cyclic_capture(truth, fabricated), noise, holes,
                                    mask.pattern.n * mask.pattern.n, noise_rng);
    write_plane(dir / "capture.npy", capture);

    const std::string d = (dir / "dec");
    auto r = run_cli("score " + mask_path +
                     " --metrics analytic --snr 50 --robust size=44um,jitter=2um --prior natural "
                     "--prior-scenes 8 --robust-decoder " +
                     d);
    REQUIRE(r.exit_code == 0);
    r = run_cli("decode " + (dir / "capture.npy") + " --psf " + d + "/robust-psf.npy --nsr-map " +
                d + "/robust-nsr.npy -o " + (dir / "x.npy"));
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    const double cli_psnr = psnr_from_mse(mse(read_plane(dir / "x.npy"), truth));

    const ScenePrior prior = make_scene_prior(parse_prior_spec("natural", 8), m);
    const RobustWienerModel model(mask, e, prior, noise);
    const ComplexPlane g = model.robust_filter_response(pattern_spectrum(mask.pattern));
    const FabricatedQuality q =
        fabricated_filter_quality(mask, e, {{"natural-7001", Image(truth)}}, noise, g, 1, seed);
    CAPTURE(cli_psnr);
    CAPTURE(q.fabricated_psnr_db);
    CHECK(std::abs(cli_psnr - q.fabricated_psnr_db) <= kLoopPsnrToleranceDb);
    MESSAGE("robust loop at 50 dB: CLI " << cli_psnr << " dB, library " << q.fabricated_psnr_db
                                         << " dB, difference "
                                         << std::abs(cli_psnr - q.fabricated_psnr_db) << " dB");

    // The float32 TIFF of the PSF decodes within float32 rounding of it.
    r = run_cli("decode " + (dir / "capture.npy") + " --psf " + d + "/robust-psf.tiff --nsr-map " +
                d + "/robust-nsr.npy -o " + (dir / "xt.npy"));
    REQUIRE(r.exit_code == 0);
    const double tiff_psnr = psnr_from_mse(mse(read_plane(dir / "xt.npy"), truth));
    MESSAGE("with robust-psf.tiff: " << tiff_psnr << " dB, difference "
                                     << std::abs(tiff_psnr - q.fabricated_psnr_db) << " dB");
    CHECK(std::abs(tiff_psnr - q.fabricated_psnr_db) <= kLoopPsnrToleranceDb);
}

TEST_CASE("search --objective robust-filter: optimises the robust design, writes its decoder") {
    TempDir dir{"robustfilter"};
    const std::string args =
        "search --grid 8 --holes 5 --pixels-per-cell 4 --tiles 1 --prior-scenes 2 --threads 1 "
        "--top 2 --seed 4 --evals 300 --rerank-scenes letter-R --no-rerank-tv --quiet --snr 30 "
        "--robust size=44um,jitter=20um,missing=0.05 --objective robust-filter ";
    auto r = run_cli(args + "--json -o " + (dir / "a"));
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    const double figure = j["ranked"][0]["analytic_robust_filter_psnr_db"].get<double>();
    CHECK(j["ranked"][0]["objective"].get<double>() == doctest::Approx(-figure));
    CHECK(j["robust_decoder"]["nsr_map"] ==
          (dir.path / "a" / "rank-1.robust-decoder" / "robust-nsr.npy").string());
    const auto config = nlohmann::json::parse(test::slurp(dir.path / "a" / "search.config.json"));
    CHECK(config["objective"] == "robust-filter");

    // The figure is the library's robust-filter figure of the written mask, and its decoder
    // files are that model's inputs, exactly.
    const Mask mask = io::read_mask_file(dir.path / "a" / "rank-1.mask.json");
    NoiseModel noise;
    noise.snr_db = 30.0;
    const FabricationErrors e{44e-6, 20e-6, 0.05};
    const RobustWienerModel model(mask, e, make_scene_prior(parse_prior_spec("natural", 2), 32),
                                  noise);
    const ComplexPlane p = pattern_spectrum(mask.pattern);
    CHECK(model.evaluate_robust_filter(p).psnr_db == doctest::Approx(figure).epsilon(1e-12));
    // The filter chosen for the errors beats the nominal PSF's filter on the same mask.
    CHECK(figure > model.evaluate(p, {WienerFilterKind::kOptimal, 0.0}).psnr_db);
    const RobustDecoderInputs in = model.robust_decoder_inputs(p);
    const fs::path d = dir.path / "a" / "rank-1.robust-decoder";
    // Rounding only: the search's pattern sums its pinholes in its own order.
    CHECK((read_plane(d / "robust-nsr.npy") - in.nsr).abs().maxCoeff() <=
          kRoundingTolerance * in.nsr.maxCoeff());
    CHECK((read_plane(d / "robust-psf.npy") - in.psf).abs().maxCoeff() <=
          kRoundingTolerance * in.psf.maxCoeff());
    // Without errors there is nothing to be robust to: refused, nothing written.
    const auto bare = run_cli(
        "search --grid 8 --holes 5 --pixels-per-cell 4 --evals 10 --quiet "
        "--objective robust-filter -o " +
        (dir / "none"));
    CHECK(bare.exit_code == 2);
    CHECK(bare.err.find("--objective = robust-filter") != std::string::npos);
    CHECK(!fs::exists(dir.path / "none" / "rank-1.robust-decoder"));
    // Same seed, same bytes.
    REQUIRE(run_cli(args + "-o " + (dir / "b")).exit_code == 0);
    for (const char* f : {"rank-1.mask.json", "rank-1.robust-decoder/robust-nsr.npy",
                          "rank-1.robust-decoder/robust-psf.tiff"})
        CHECK(test::slurp(dir.path / "a" / f) == test::slurp(dir.path / "b" / f));
}

}  // namespace pinmask
