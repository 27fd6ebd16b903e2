// `pinmask decode` end to end on synthetic captures made here: a PSF from a small pinhole
// pattern, the capture its circular convolution with a known scene (direct sum, deconvwnr
// centring), tiled over a frame larger than one period where the test needs it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "cli/options/flag_names.hpp"
#include "core/fft/fft.hpp"
#include "core/image/image_io.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/capture/decoder.hpp"
#include "tests/support/cli_run.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// Noise-free capture, NSR 1e-9 against |H| >= kMinOtfAbs: the Wiener estimate differs from the
// scene by ~NSR / |H|^2 relative per frequency plus float32 file round-off (~6e-8) amplified by
// at most 1 / kMinOtfAbs, far above 60 dB; 60 dB still fails for any wrong shift, crop or
// centring convention (those give ~10-20 dB).
constexpr double kExactDecodePsnrDb = 60.0;
constexpr double kNsr = 1e-9;
// The test PSF's smallest |H| (0.0157, measured when the pattern was chosen): well clear of the
// exact zeros a box pinhole whose width divides the period would put into H.
constexpr double kMinOtfAbs = 0.01;

// decode --mask synthesises the PSF in double; the reference decode here uses the float32 PSF
// file of `pinmask psf` (relative difference ~6e-8). With NSR 1e-3 the Wiener gain is at most
// 1 / (2 sqrt(NSR)) = 16, so the two estimates agree to ~1e-6 of their maximum.
constexpr double kMaskVsFileDecodeTol = 1e-5;
constexpr double kMaskNsr = 1e-3;
// Against the scene itself: NSR 1e-3 gives up the PSF's weak frequencies (measured 27.8 dB).
constexpr double kMaskScenePsnrDb = 20.0;

// The test pattern: a 25 x 25 PSF (odd: exercises the floor(n/2) centring) of 2 x 2 pinholes.
constexpr int kN = 25;

Plane pattern_psf() {
    Plane psf = Plane::Zero(kN, kN);
    const int holes[][2] = {{5, 7}, {14, 20}, {5, 20}, {15, 0}, {19, 17}, {15, 21}, {6, 17}};
    for (const auto& h : holes) psf.block(h[0], h[1], 2, 2) = 1.0;
    return psf / psf.sum();
}

Plane smooth_scene(int n, double phase) {
    Plane s(n, n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            s(r, c) = 2.0 + std::sin(2 * std::numbers::pi * r / n + phase) +
                      0.5 * std::cos(4 * std::numbers::pi * c / n) + (r > n / 2 && c < n / 3);
    return s;
}

// p(r, c) = sum_{i, j} x(i, j) a((r - i + n/2) mod n, (c - j + n/2) mod n): circular
// convolution with the PSF's central element at the origin (deconvwnr / imfilter 'circular').
Plane circular_capture(const Plane& x, const Plane& a) {
    const int n = static_cast<int>(x.rows()), h = n / 2;
    Plane p = Plane::Zero(n, n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j)
                    p(r, c) += x(i, j) * a(((r - i + h) % n + n) % n, ((c - j + h) % n + n) % n);
    return p;
}

// The period repeated over rows x cols, frame pixel (r, c) = period((r + r0) mod n, (c + c0) mod
// n).
Plane tile(const Plane& period, int rows, int cols, int r0, int c0) {
    Plane out(rows, cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            out(r, c) = period((r + r0) % period.rows(), (c + c0) % period.cols());
    return out;
}

double psnr_db(const Plane& x, const Plane& ref) {
    const double mse = (x - ref).square().mean();
    return 10.0 * std::log10(ref.square().maxCoeff() / std::max(mse, 1e-300));
}

void write_float(const std::string& path, const Image& img) {
    write_tiff(path, img, SampleFormat::kFloat32);
}

nlohmann::json read_json(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("decode of one period returns the scene (Wiener, float TIFF out, stats keys)") {
    TempDir dir("cli-decode");
    const Plane psf = pattern_psf();
    REQUIRE(Fft2(kN, kN).forward(psf).abs().minCoeff() >= kMinOtfAbs);
    const Plane scene = smooth_scene(kN, 0.3);
    write_float(dir / "psf.tiff", Image(psf));
    write_float(dir / "cap.tiff", Image(circular_capture(scene, psf)));
    // A PSF file without pinmask's sidecar that covers the capture is read as a lensless
    // camera's (--model auto: linear); this one is one period of a tiling.
    const auto r =
        run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                " --model cyclic --nsr 1e-9 -o " + dir / "x.tiff" + " --stats " + dir / "s.json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const Plane x = read_image(dir / "x.tiff").image.channels.at(0);
    CHECK(psnr_db(x, scene) >= kExactDecodePsnrDb);

    const auto s = read_json(dir / "s.json");
    for (const char* k : {"load", "dark", "preprocess", "period_check", "crop", "decode",
                          "decode_channels", "write", "total"})
        CHECK_MESSAGE(s["timings_s"].contains(k), k);
    CHECK(s["method"] == "wiener");
    CHECK(s["config"]["nsr"] == kNsr);
    CHECK(s["channels"].size() == 1);
    for (const char* k : {"iterations", "objective", "residual", "converged", "constraint_met"})
        CHECK_MESSAGE(s["channels"][0].contains(k), k);
    // Wall-clock figures live only under timings_s (the rest of the stats is deterministic).
    CHECK_FALSE(s["channels"][0].contains("seconds"));
    CHECK(s["timings_s"]["decode_channels"].size() == 1);
    CHECK(s["precision"] == "double");
    // One period in the frame: the period check is skipped, with the reason.
    CHECK(s["period_check"]["checked"] == false);
    CHECK(s["period_check"]["rows"]["skip_reason"].get<std::string>().find("needs at least 2") !=
          std::string::npos);
    // --json prints the same stats on stdout.
    const auto j = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                           " --model cyclic --nsr 1e-9 -o " + dir / "x2.tiff --json");
    REQUIRE(j.exit_code == 0);
    const auto js = nlohmann::json::parse(j.out);
    CHECK(js["format"] == "pinmask-decode-stats");
    CHECK(js["channels"][0]["residual"] == s["channels"][0]["residual"]);
    // The resolved configuration sits next to the output.
    const auto cfg = read_json(dir / "x.tiff.config.json");
    // --method as given (auto, the default); the method that ran, implied by --nsr, in the stats.
    CHECK(cfg["method"] == "auto");
    CHECK(s["method"] == "wiener");
    CHECK(cfg["chosen"]["method"]["value"] == "wiener");
    CHECK(cfg["chosen"]["method"]["reason"].get<std::string>().find("--nsr given: only wiener") ==
          0);
    CHECK(cfg["crop"] == "auto");
    CHECK(cfg["model"] == "cyclic");
    // What auto chose, and why: the whole frame (the PSF covers it); a float PSF has no floor.
    CHECK(cfg["chosen"]["crop"]["value"] == "none");
    CHECK(cfg["chosen"]["background"]["value"] == "none");
    CHECK_FALSE(cfg["chosen"].contains("model"));
    CHECK(s["chosen"] == cfg["chosen"]);
    // Every choice is recorded, defaults included: the RAW demosaic and the normalisation.
    CHECK(cfg["bayer"] == "sum2x2");
    CHECK(cfg["normalize"] == "none");
    CHECK(s["config"]["bayer"] == "sum2x2");
    CHECK(s["preprocess"]["bayer"] == "sum2x2");
    CHECK(s["preprocess"]["normalize"]["mode"] == "none");
    // --bayer given with a TIFF capture reads it as a mosaic: green needs the colour-filter
    // pattern a TIFF does not hold, so it is refused, never silently ignored.
    const auto g = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                           " --model cyclic --nsr 1e-9 --bayer green -o " + dir / "x3.tiff");
    CHECK(g.exit_code == 2);
    CHECK(g.err.find("--bayer = green") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "x3.tiff"));
}

TEST_CASE("decode crops the centred period of a tiled RGB frame and checks the period") {
    TempDir dir("cli-decode-rgb");
    const Plane psf = pattern_psf();
    const int rows = 2 * kN + 13, cols = 3 * kN + 5, r0 = 7, c0 = 11;
    Image cap(rows, cols, 3);
    std::vector<Plane> scenes;
    for (int ch = 0; ch < 3; ++ch) {
        scenes.push_back(smooth_scene(kN, 1.1 * ch));
        cap.channels[ch] = tile(circular_capture(scenes[ch], psf), rows, cols, r0, c0);
    }
    write_float(dir / "psf.tiff", Image(psf));
    write_float(dir / "cap.tiff", cap);
    const auto r = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                           " --nsr 1e-9 -o " + dir / "x.tiff" + " --stats " + dir / "s.json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("warning") == std::string::npos);
    const Image x = read_image(dir / "x.tiff").image;
    REQUIRE(x.n_channels() == 3);
    // The window starts at ((R - N) / 2, (C - N) / 2); it holds the period shifted by the
    // window corner plus the tiling phase, and so does the scene it decodes to.
    const int wr = (rows - kN) / 2, wc = (cols - kN) / 2;
    for (int ch = 0; ch < 3; ++ch) {
        const Plane expected = tile(scenes[ch], kN, kN, (wr + r0) % kN, (wc + c0) % kN);
        INFO("channel " << ch);
        CHECK(psnr_db(x.channels[ch], expected) >= kExactDecodePsnrDb);
    }
    const auto s = read_json(dir / "s.json");
    CHECK(s["window"]["x"] == wc);
    CHECK(s["window"]["y"] == wr);
    CHECK(s["channels"].size() == 3);
    CHECK(s["period_check"]["checked"] == true);
    CHECK(s["period_check"]["matches"] == true);
    CHECK(s["period_check"]["rows"]["checked"] == true);
    CHECK(s["period_check"]["cols"]["checked"] == true);

    // X,Y picks the corner: column X, row Y.
    const auto rc = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                            " --crop 3,2 --nsr 1e-9 -o " + dir / "y.tiff");
    REQUIRE(rc.exit_code == 0);
    const Image y = read_image(dir / "y.tiff").image;
    CHECK(psnr_db(y.channels[1], tile(scenes[1], kN, kN, (2 + r0) % kN, (3 + c0) % kN)) >=
          kExactDecodePsnrDb);
}

TEST_CASE("a capture repeating with another period than the PSF's is reported") {
    TempDir dir("cli-decode-period");
    const int m = 29;  // the capture's true period; the PSF is kN = 25
    Plane other = Plane::Zero(m, m);
    other.block(0, 0, 4, 4) = 1.0;
    other.block(10, 17, 4, 4) = 1.0;
    other.block(20, 6, 4, 4) = 1.0;
    const Plane cap = tile(circular_capture(smooth_scene(m, 0.0), other), 100, 90, 3, 4);
    write_float(dir / "psf.tiff", Image(pattern_psf()));
    write_float(dir / "cap.tiff", Image(cap));
    const auto r = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" + " -o " +
                           dir / "x.png" + " --stats " + dir / "s.json");
    REQUIRE(r.exit_code == 0);  // reported, not refused
    CHECK(r.err.find("warning") != std::string::npos);
    CHECK(r.err.find("PSF period is 25") != std::string::npos);
    const auto s = read_json(dir / "s.json");
    CHECK(s["period_check"]["matches"] == false);
    CHECK(std::fabs(s["period_check"]["rows"]["measured_px"].get<double>() - m) <= 0.5);
    CHECK(std::fabs(s["period_check"]["cols"]["measured_px"].get<double>() - m) <= 0.5);
    // PNG output: scaled by the maximum, so the brightest pixel is full white.
    const LoadedImage png = read_image(dir / "x.png");
    CHECK(png.format == SampleFormat::kUint8);
    CHECK(png.image.channels[0].maxCoeff() == 255.0);
}

TEST_CASE("bad input exits 2 naming the problem and leaves no output") {
    TempDir dir("cli-decode-bad");
    const Plane psf = pattern_psf();
    const Plane cap = circular_capture(smooth_scene(kN, 0.2), psf);
    write_float(dir / "psf.tiff", Image(psf));
    write_float(dir / "cap.tiff", Image(cap));
    write_float(dir / "zero.tiff", Image(Plane::Zero(kN, kN)));
    write_float(dir / "neg.tiff", Image(Plane(-psf)));
    write_float(dir / "small.tiff", Image(Plane(cap.topLeftCorner(kN - 1, kN))));
    write_float(dir / "dark_other.tiff", Image(Plane::Zero(kN + 1, kN)));
    Plane nan = cap;
    nan(3, 4) = std::numeric_limits<double>::quiet_NaN();
    write_float(dir / "nan.tiff", Image(nan));
    Plane inf = cap;
    inf(5, 6) = std::numeric_limits<double>::infinity();
    write_float(dir / "inf.tiff", Image(inf));
    { std::ofstream(dir / "empty.tiff"); }
    {
        const std::string bytes = test::slurp(dir / "cap.tiff");
        std::ofstream(dir / "trunc.tiff", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    }
    const std::string psf_arg = " --psf " + dir / "psf.tiff --model cyclic";
    const std::pair<std::string, std::string> cases[] = {
        {dir / "small.tiff" + psf_arg, "smaller than one period"},
        {dir / "nan.tiff" + psf_arg, "NaN"},
        {dir / "inf.tiff" + psf_arg, "infinite"},
        {dir / "empty.tiff" + psf_arg, "empty.tiff"},
        {dir / "trunc.tiff" + psf_arg, "trunc.tiff"},
        {dir / "cap.tiff --model cyclic --psf " + dir / "zero.tiff", "sums to"},
        {dir / "cap.tiff --model cyclic --psf " + dir / "neg.tiff", "sums to"},
        {dir / "cap.tiff" + psf_arg + " --method magic", "magic"},
        {dir / "cap.tiff" + psf_arg + " --method rl", "richardson-lucy"},  // one spelling
        // A flag the method does not read: refused naming the flag, the method and its users.
        {dir / "cap.tiff" + psf_arg + " --method tv --nsr 0.1",
         "--nsr = 0.1: is not used by --method tv (only by wiener)"},
        {dir / "cap.tiff" + psf_arg + " --method wiener --lambda 0.1",
         "--lambda = 0.1: is not used by --method wiener (only by tikhonov, tv)"},
        // --method auto (the default): a flag neither wiener nor tv reads, or two that disagree.
        {dir / "cap.tiff" + psf_arg + " --regulariser gradient",
         "--regulariser = gradient: is not used by --method auto (wiener or tv, chosen from the "
         "capture; only by tikhonov); give --method tikhonov"},
        {dir / "cap.tiff" + psf_arg + " --nsr 0.1 --iters 3",
         "--iters = 3: is read by tv but --nsr 0.1 is read by wiener only; give --method"},
        {dir / "cap.tiff" + psf_arg + " --method tv --regulariser gradient", "--regulariser"},
        {dir / "cap.tiff" + psf_arg + " --method tv --eps 1", "(only by tvqc)"},
        {dir / "cap.tiff" + psf_arg + " --method richardson-lucy --noise-sigma 1", "--noise-sigma"},
        {dir / "cap.tiff" + psf_arg + " --method tikhonov --nonneg", "(only by tv, tvqc)"},
        {dir / "cap.tiff" + psf_arg + " --method wiener --iters 3",
         "(only by tv, tvqc, richardson-lucy)"},
        {dir / "cap.tiff" + psf_arg + " --method tikhonov --tol 0.1", "--tol"},
        {dir / "cap.tiff" + psf_arg + " --method tikhonov --lambda 0",
         "(use --method wiener --nsr 0 for the floored inverse)"},
        {dir / "cap.tiff" + psf_arg + " --dark " + dir / "dark_other.tiff", "dark frame"},
        {dir / "cap.tiff" + psf_arg + " --crop 1,0", "crop"},
        {dir / "cap.tiff" + psf_arg + " --crop middle", "--crop"},
        {dir / "cap.tiff" + psf_arg + " --scale -1", "--scale"},
        {dir / "cap.tiff", "PSF"},
    };
    for (const auto& c : cases) {
        const std::string& args = c.first;
        const std::string& needle = c.second;
        const auto r =
            run_cli("decode " + args + " -o " + dir / "out.png" + " --stats " + dir / "s.json");
        INFO(args);
        INFO(r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(needle) != std::string::npos);
        CHECK_FALSE(fs::exists(dir / "out.png"));
        CHECK_FALSE(fs::exists(dir / "out.png.config.json"));
        CHECK_FALSE(fs::exists(dir / "s.json"));
    }
    // An unknown output extension is refused before any work.
    const auto r = run_cli("decode " + dir / "cap.tiff" + psf_arg + " -o " + dir / "out.jpg");
    CHECK(r.exit_code == 2);
    CHECK_FALSE(fs::exists(dir / "out.jpg"));
    // Only our files and the inputs remain: no temporaries.
    for (const auto& e : fs::directory_iterator(dir.path))
        CHECK(e.path().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("decode --mask synthesises the mask's PSF (the one `pinmask psf` writes)") {
    TempDir dir("cli-decode-mask");
    const std::string mask = dir / "m.mask.json";
    REQUIRE(run_cli("generate --grid 8 --holes 6 --tiles 2 --pixels-per-cell 4 --seed 3 -o " + mask)
                .exit_code == 0);
    REQUIRE(run_cli("psf " + mask + " -o " + dir / "psf.tiff").exit_code == 0);
    const Plane psf = read_image(dir / "psf.tiff").image.channels.at(0);
    const int n = static_cast<int>(psf.rows());
    REQUIRE(n == 32);
    const Plane scene = smooth_scene(n, 0.7);
    const int rows = 3 * n + 7, cols = 2 * n + 9, r0 = 5, c0 = 20;
    write_float(dir / "cap.tiff", Image(tile(circular_capture(scene, psf), rows, cols, r0, c0)));
    const auto r = run_cli("decode " + dir / "cap.tiff" + " --mask " + mask + " --nsr 1e-3 -o " +
                           dir / "x.tiff" + " --stats " + dir / "s.json");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    // The reference: the centred window decoded in-process with the PSF file.
    const int wr = (rows - n) / 2, wc = (cols - n) / 2;
    const Plane window = read_image(dir / "cap.tiff").image.channels.at(0).block(wr, wc, n, n);
    DecodeOptions o;
    o.wiener.nsr = kMaskNsr;
    const Plane ref = decode_plane(window, psf, o).image;
    const Plane x = read_image(dir / "x.tiff").image.channels.at(0);
    CHECK(test::max_rel_error(x, ref) <= kMaskVsFileDecodeTol);
    // And the scene is there: the PSF has near-zeros (min |H| ~ 2e-10), so not exactly.
    const Plane expected = tile(scene, n, n, (wr + r0) % n, (wc + c0) % n);
    CHECK(psnr_db(x, expected) >= kMaskScenePsnrDb);
    const auto s = read_json(dir / "s.json");
    CHECK(s["psf"]["source"] == "mask");
    CHECK(s["period_check"]["matches"] == true);

    // A synthesised PSF has no camera background to take from its corner.
    const auto bad = run_cli("decode " + dir / "cap.tiff" + " --mask " + mask +
                             " --background corner -o " + dir / "y.png");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--background") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "y.png"));
}

TEST_CASE("bench plan fills the wisdom cache; a corrupt cache is ignored with a warning") {
    TempDir dir("cli-wisdom");
    const std::string wisdom = (dir.path / "cache" / "wisdom").string();
    ::setenv("PINMASK_WISDOM", wisdom.c_str(), 1);
    const auto first = run_cli("bench plan --sizes 24 --no-linear");
    INFO(first.err);
    CHECK(first.exit_code == 0);
    CHECK(first.out.find("measured") != std::string::npos);
    CHECK(std::filesystem::exists(wisdom));
    const auto second = run_cli("bench plan --sizes 24 --no-linear");
    CHECK(second.exit_code == 0);
    CHECK(second.out.find("wisdom") != std::string::npos);
    CHECK(second.out.find("measured") == std::string::npos);
    { std::ofstream(wisdom, std::ios::binary) << "not wisdom at all"; }
    const auto corrupt = run_cli("bench plan --sizes 24 --no-linear");
    CHECK(corrupt.exit_code == 0);
    CHECK(corrupt.err.find("ignored") != std::string::npos);
    CHECK(corrupt.out.find("measured") != std::string::npos);
    ::setenv("PINMASK_WISDOM", "off", 1);
}

TEST_CASE("--precision single applies to tvqc and richardson-lucy (no longer double only)") {
    TempDir dir("cli-decode-precision");
    const Plane psf = pattern_psf();
    write_float(dir / "psf.tiff", Image(psf));
    write_float(dir / "cap.tiff", Image(circular_capture(smooth_scene(kN, 0.1), psf)));
    for (const char* method : {"tvqc --eps 0.5", "richardson-lucy"}) {
        for (const char* precision : {"single", "double"}) {
            const auto r = run_cli("decode " + dir / "cap.tiff" + " --psf " + dir / "psf.tiff" +
                                   " --method " + method + " --iters 5 --precision " + precision +
                                   " -o " + dir / "x.tiff" + " --stats " + dir / "s.json");
            INFO(method << " " << precision << ": " << r.err);
            REQUIRE(r.exit_code == 0);
            CHECK(read_json(dir / "s.json")["precision"] == precision);
        }
    }
}

TEST_CASE("decode's library fields are spelled as the flags that set them") {
    // The decode library names its request's fields (decode/capture/decode_request.hpp); the
    // command line spells each one as its flag, so its messages name the flags as before.
    const std::pair<MethodParameter, const char*> flags[] = {
        {MethodParameter::kNsr, "--nsr"},
        {MethodParameter::kLambda, "--lambda"},
        {MethodParameter::kRegulariser, "--regulariser"},
        {MethodParameter::kEps, "--eps"},
        {MethodParameter::kNoiseSigma, "--noise-sigma"},
        {MethodParameter::kNonnegative, "--nonneg"},
        {MethodParameter::kIterations, "--iters"},
        {MethodParameter::kTolerance, "--tol"},
    };
    for (const auto& row : flags) {
        const std::string flag = row.second;  // a copy: clang cannot capture a structured binding
        INFO(flag);
        CHECK(cli::flag_spelling(method_parameter_field(row.first)) == flag);
    }
    DecodeRequest r;
    r.method = DecodeMethod::kTv;
    try {
        refuse_unused_parameters(r, {{MethodParameter::kNsr, "0.1"}});
        FAIL("accepted");
    } catch (const InvalidInput& e) {
        CHECK(cli::spell_flags(e.what()) ==
              "--nsr = 0.1: is not used by --method tv (only by wiener); remove it or choose "
              "that method");
    }
}
