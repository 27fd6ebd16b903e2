// `pinmask psf` end to end, and the PSF file reader (io/psf_files) the decoder uses.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
using pinmask::test::run_cli;
using pinmask::test::slurp;
using pinmask::test::TempDir;
namespace fs = std::filesystem;

namespace {

// float32 storage rounds each value to ~6e-8 relative.
constexpr double kFloatTol = 1e-6;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

Mask sample_mask() {
    Mask m;
    m.pattern.n = 16;
    m.pattern.pinholes = {{0, 0}, {0, 5}, {3, 9}, {7, 2}, {9, 12}, {14, 14}};
    m.camera = paper_camera();
    m.psf.pixels_per_cell = 8;
    m.provenance.generator = "test";
    m.provenance.family = "random";
    return m;
}

std::string write_mask(const TempDir& dir, const Mask& m, const std::string& name = "m.mask.json") {
    const std::string path = dir / name;
    io::write_mask_file(path, m);
    return path;
}

std::size_t file_count(const TempDir& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++n;
    return n;
}

}  // namespace

TEST_CASE("psf writes TIFF, npy and sidecar; sizes right, sum 1, same as the library") {
    TempDir dir("psf");
    const Mask m = sample_mask();
    const std::string mask = write_mask(dir, m);
    const auto ok = run_cli("psf " + mask + " -o " + (dir / "psf.tiff") + " --npy");
    INFO(ok.err);
    REQUIRE(ok.exit_code == 0);
    CHECK(contains(ok.out, "psf.json"));
    const io::PsfFile f = io::read_psf_file(dir / "psf.tiff");
    CHECK(f.psf.rows() == 128);
    CHECK(f.psf.cols() == 128);
    CHECK(std::fabs(f.psf.sum() - 1) <= 1e-12);
    REQUIRE(f.sidecar.has_value());
    const io::PsfSidecar& s = *f.sidecar;
    CHECK(s.mask_geometry_hash == geometry_hash(m));
    CHECK(s.pixels_per_cell == 8);
    CHECK(s.grid_n == 16);
    CHECK(s.pixel_pitch_m == 30e-6);
    CHECK(s.kernel_model == "fresnel");
    CHECK(s.wavelengths.size() == 1);
    CHECK(s.wavelengths[0].first == 550e-9);
    CHECK(s.normalisation == "sum=1");
    CHECK(s.npy_file == "psf.npy");
    const Plane lib = mask_psf(m);
    CHECK((f.psf - lib).abs().maxCoeff() <= kFloatTol * lib.maxCoeff());
    const io::PsfFile npy = io::read_psf_file(dir / "psf.npy");
    CHECK((npy.psf - f.psf).abs().maxCoeff() == 0.0);
    // The raw file values are the float32 PSF: their sum is 1 up to float rounding.
    const LoadedImage raw = read_image(dir / "psf.tiff");
    CHECK(raw.format == SampleFormat::kFloat32);
    CHECK(std::fabs(raw.image.channels[0].sum() - 1) <= kFloatTol);
    // Deterministic: a second run gives identical bytes.
    const std::string first = slurp(dir / "psf.tiff"), first_json = slurp(dir / "psf.json");
    REQUIRE(run_cli("psf " + mask + " -o " + (dir / "psf.tiff") + " --npy").exit_code == 0);
    CHECK(slurp(dir / "psf.tiff") == first);
    CHECK(slurp(dir / "psf.json") == first_json);
}

TEST_CASE("psf --kernel overrides the mask's model; f = f' and u = inf work") {
    TempDir dir("psf-kernel");
    const std::string mask = write_mask(dir, sample_mask());
    const auto box = run_cli("psf " + mask + " -o " + (dir / "box.tif") + " --kernel box --json");
    REQUIRE(box.exit_code == 0);
    const auto j = nlohmann::json::parse(box.out);
    CHECK(j["kernel"]["model"] == "box");
    CHECK(j["kernel"]["enclosed_energy"] == 1.0);
    CHECK(!fs::exists(dir / "box.npy"));
    Mask lim = sample_mask();
    lim.camera.lens_focal_m = lim.camera.sensor_distance_m;
    lim.camera.object_distance_m = INFINITY;
    const std::string lim_path = write_mask(dir, lim, "lim.mask.json");
    const auto r = run_cli("psf " + lim_path + " -o " + (dir / "lim.tiff"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const io::PsfFile f = io::read_psf_file(dir / "lim.tiff");
    CHECK(f.sidecar->kernel_model == "fraunhofer");
    CHECK(is_all_finite(f.psf));
}

TEST_CASE("errors exit 2 and leave no files") {
    TempDir dir("psf-err");
    const std::string mask = write_mask(dir, sample_mask());
    auto refused = [&](const std::string& args, const std::string& says) {
        const auto r = run_cli("psf " + args);
        INFO(args << " -> " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, says));
        CHECK(file_count(dir) == 1);  // only the mask
    };
    refused(mask + " -o " + (dir / "p.tiff") + " --kernel measured", "--kernel-path");
    refused(mask + " -o " + (dir / "p.tiff") + " --kernel gauss", "--kernel");
    refused(mask + " -o " + (dir / "p.png"), "-o");
    refused(mask + " -o " + (dir / "nodir/p.tiff"), "folder");
    refused((dir / "missing.mask.json") + " -o " + (dir / "p.tiff"), "missing.mask.json");
    refused(mask + " -o " + (dir / "p.tiff") + " --kernel measured --kernel-path " +
                (dir / "nokernel.npy"),
            "nokernel.npy");
    ::setenv("PINMASK_MEMORY_LIMIT", "64K", 1);
    refused(mask + " -o " + (dir / "p.tiff"), "memory");
    ::unsetenv("PINMASK_MEMORY_LIMIT");
}

TEST_CASE("read_psf_file validates the image and the sidecar") {
    TempDir dir("psf-read");
    const std::string mask = write_mask(dir, sample_mask());
    REQUIRE(run_cli("psf " + mask + " -o " + (dir / "p.tiff")).exit_code == 0);
    const std::string good = slurp(dir / "p.json");
    auto with_sidecar = [&](const std::string& text) {
        std::ofstream(dir / "p.json", std::ios::binary) << text;
    };
    auto replace = [](std::string s, const std::string& from, const std::string& to) {
        const auto at = s.find(from);
        REQUIRE(at != std::string::npos);
        return s.replace(at, from.size(), to);
    };
    with_sidecar(replace(good, "\"pinmask-psf\"", "\"pinmask-mask\""));
    CHECK_THROWS_AS(io::read_psf_file(dir / "p.tiff"), InvalidInput);
    with_sidecar(replace(good, "\"version\": 1", "\"version\": 2"));
    CHECK_THROWS_AS(io::read_psf_file(dir / "p.tiff"), InvalidInput);
    with_sidecar(replace(good, "\"version\": 1", "\"version\": 1, \"colour\": \"red\""));
    CHECK_THROWS_AS(io::read_psf_file(dir / "p.tiff"), InvalidInput);
    with_sidecar(replace(good, "\"size_px\": [128, 128]", "\"size_px\": [128, 64]"));
    CHECK_THROWS_AS(io::read_psf_file(dir / "p.tiff"), InvalidInput);
    with_sidecar("{ not json");
    CHECK_THROWS_AS(io::read_psf_file(dir / "p.tiff"), InvalidInput);
    fs::remove(dir / "p.json");
    CHECK_FALSE(io::read_psf_file(dir / "p.tiff").sidecar.has_value());
    // Bad image data.
    Plane bad = Plane::Ones(4, 4);
    bad(1, 1) = NAN;
    write_npy(dir / "nan.npy", Image(bad), SampleFormat::kFloat64);
    CHECK_THROWS_AS(io::read_psf_file(dir / "nan.npy"), InvalidInput);
    write_npy(dir / "zero.npy", Image(Plane::Zero(4, 4)), SampleFormat::kFloat64);
    CHECK_THROWS_AS(io::read_psf_file(dir / "zero.npy"), InvalidInput);
    CHECK_THROWS_AS(io::read_psf_file(dir / "none.tiff"), InvalidInput);
}

TEST_CASE("psf --geometry exact --object-distance 6m: spot centroids within 0.05 px of Eq. (3)") {
    // The required bound on a spot centroid against its Eq. (3) position.
    constexpr double kCentroidTolPx = 0.05;
    TempDir dir("psf-exact");
    const Mask m = sample_mask();
    const std::string mask = write_mask(dir, m);
    const auto r = run_cli("psf " + mask + " -o " + (dir / "e.tiff") +
                           " --geometry exact --object-distance 6m --kernel box --size 400x500");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const Plane a = read_image(dir / "e.tiff").image.channels[0];
    REQUIRE(a.rows() == 400);
    REQUIRE(a.cols() == 500);
    // Eq. (3) written out: q = (1 - f/f' + f/u) s with s from the centre of the 2 x 2 tiled mask.
    const Camera& c = m.camera;
    const double mag = 1.0 - c.sensor_distance_m / c.lens_focal_m + c.sensor_distance_m / 6.0;
    const double pitch = mag * c.pinhole_m / c.pixel_pitch_m;
    auto centre = [&](int window, int cell) { return window / 2.0 + (cell + 0.5 - 16) * pitch; };
    for (int tr = 0; tr < 2; ++tr) {
        for (int tc = 0; tc < 2; ++tc) {
            for (const Cell& cell : m.pattern.pinholes) {
                const double y = centre(400, tr * 16 + cell.row);
                const double x = centre(500, tc * 16 + cell.col);
                double s = 0, sy = 0, sx = 0;
                for (int i = int(y - 1.2 * pitch); i <= int(y + 1.2 * pitch); ++i) {
                    for (int j = int(x - 1.2 * pitch); j <= int(x + 1.2 * pitch); ++j) {
                        s += a(i, j);
                        sy += a(i, j) * (i + 0.5);
                        sx += a(i, j) * (j + 0.5);
                    }
                }
                CHECK(std::fabs(sy / s - y) <= kCentroidTolPx);
                CHECK(std::fabs(sx / s - x) <= kCentroidTolPx);
            }
        }
    }
    // Flags of the exact geometry are refused with the integer one, and u inside f' exits 2.
    const auto wrong = run_cli("psf " + mask + " -o " + (dir / "w.tiff") + " --size 10x10");
    CHECK(wrong.exit_code == 2);
    CHECK(contains(wrong.err, "--geometry exact"));
    const auto inside = run_cli("psf " + mask + " -o " + (dir / "w.tiff") +
                                " --geometry exact --object-distance 10cm");
    CHECK(inside.exit_code == 2);
    CHECK(contains(inside.err, "focal length"));
    CHECK(!fs::exists(dir / "w.tiff"));
}

TEST_CASE("simulate --geometry exact: sensor-sized capture, decode gives no false period warning") {
    // The paper camera at its 6 m: the sample mask's pinhole puts 8.079 px per cell there (period
    // 129.26 px, 1 % off the 128 px PSF: a true mismatch, reported with both figures); the
    // pinhole solved for 8 px per cell at 6 m (design --pixels-per-cell 8) makes the capture's
    // period the PSF's (no warning).
    TempDir dir("sim-exact");
    Mask whole = sample_mask();
    whole.camera.pinhole_m = pinhole_for_pixels_per_cell(whole.camera, 8);
    for (const bool matched : {true, false}) {
        const std::string mask = write_mask(dir, matched ? whole : sample_mask(),
                                            matched ? "w.mask.json" : "m.mask.json");
        const std::string capture = dir / (matched ? "w.npy" : "c.npy");
        const auto r = run_cli("simulate " + mask + " -o " + capture +
                               " --geometry exact --object-distance 6m --snr 30");
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        const Plane c = read_image(capture).image.channels[0];
        CHECK(c.rows() == 480);
        CHECK(c.cols() == 720);
        const auto d = run_cli("decode " + capture + " --mask " + mask + " -o " +
                               (dir / (matched ? "w.png" : "d.png")));
        INFO(d.err);
        CHECK(d.exit_code == 0);
        if (matched) {
            CHECK_FALSE(contains(d.err, "warning"));
        } else {
            CHECK(contains(d.err, "warning: the capture repeats every 129."));
            CHECK(contains(d.err, "the PSF period is 128 px"));
        }
    }
    const std::string mask = dir / "m.mask.json";
    const auto bad =
        run_cli("simulate " + mask + " -o " + (dir / "x.npy") + " --geometry exact --full-sensor");
    CHECK(bad.exit_code == 2);
    CHECK(contains(bad.err, "--full-sensor"));
    CHECK(!fs::exists(dir / "x.npy"));
}
