// `pinmask calibrate` end to end: a point-source capture from the independent forward model,
// written as a float TIFF, calibrated; its outputs read back; `decode --psf DIR/psf.tiff` with no
// other flag; bad input refused with exit 2 and no output folder.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>

#include "core/image/image_io.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/families.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"
#include "tests/decode/calibrate/point_source_model.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

struct Fixture {
    fs::path dir;
    test::PointSourceScene scene;
    Fixture() {
        dir = fs::temp_directory_path() / ("pinmask-cal-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        std::mt19937_64 rng(4);
        Mask m;
        m.pattern = paper_pattern(rng);
        m.camera = paper_camera();
        m.psf.kernel.model = "box";
        m.provenance.generator = "test";
        m.provenance.family = "paper";
        io::write_mask_file(dir / "m.mask.json", m);
        scene.pattern = m.pattern;
        scene.rows = 300;
        scene.cols = 310;
        scene.rotation_deg = 0.5;
        scene.pitch_x = scene.pitch_y = 8.04;
        scene.x0 = 25.3;
        scene.y0 = 24.6;
        scene.snr_db = 40;
        scene.leak = 5;
        scene.dark = 20;
        scene.missing = {{m.pattern.pinholes[0].row, m.pattern.pinholes[0].col}};
        write_tiff(dir / "point.tiff", Image(test::point_source_capture(scene)),
                   SampleFormat::kFloat32);
    }
    ~Fixture() { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
};

}  // namespace

TEST_CASE("pinmask calibrate: outputs, JSON keys, decode --psf") {
    Fixture f;
    const auto r = test::run_cli("calibrate " + f.p("point.tiff") + " --mask " +
                                 f.p("m.mask.json") + " -o " + f.p("cal") + " --json");
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"rotation_deg", "pitch_px", "position_px", "missing_pinholes",
                            "extra_spots", "background", "kernel_fit", "psf"})
        CHECK_MESSAGE(j.contains(key), key);
    CHECK(std::abs(j["rotation_deg"].get<double>() - 0.5) < 0.03);
    CHECK(std::abs(j["pitch_px"][0].get<double>() / 8.04 - 1) < 1e-3);
    CHECK(std::abs(j["position_px"][0].get<double>() - 25.3) < 0.1);
    CHECK(j["missing_pinholes"].size() == 1);
    CHECK(j["extra_spots"].empty());
    CHECK(j["kernel_fit"].contains("box"));
    CHECK(j["psf"].get<std::string>() == (f.dir / "cal" / "psf.tiff").string());
    for (const char* file : {"psf.tiff", "psf.json", "kernel.tiff", "calibrated.mask.json",
                             "report.pdf", "calibration.json"})
        CHECK_MESSAGE(fs::exists(f.dir / "cal" / file), file);
    CHECK(!fs::exists(f.dir / "cal.tmp-calibrate"));
    // The report is a PDF with the overlay, kernel and table pages.
    CHECK(test::slurp(f.dir / "cal" / "report.pdf").rfind("%PDF", 0) == 0);
    // The PSF file and its sidecar read back; the calibrated mask records the geometry.
    const io::PsfFile psf = io::read_psf_file(f.dir / "cal" / "psf.tiff");
    CHECK(psf.psf.rows() == 300);
    CHECK(psf.psf.cols() == 310);
    REQUIRE(psf.sidecar);
    CHECK(psf.sidecar->kernel_model == "measured");
    const Mask cal = io::read_mask_file(f.dir / "cal" / "calibrated.mask.json");
    CHECK(cal.provenance.scores.at("calibrated_rotation_deg") ==
          doctest::Approx(j["rotation_deg"].get<double>()));
    CHECK(cal.provenance.scores.count("calibrated_pitch_x_px") == 1);
    // decode uses the calibrated PSF with no other flag.
    const auto d = test::run_cli("decode " + f.p("point.tiff") + " --psf " + f.p("cal/psf.tiff") +
                                 " -o " + f.p("out.tiff"));
    CHECK_MESSAGE(d.exit_code == 0, d.err);
    CHECK(fs::exists(f.dir / "out.tiff"));
    // Same inputs, same bytes.
    const auto r2 = test::run_cli("calibrate " + f.p("point.tiff") + " --mask " +
                                  f.p("m.mask.json") + " -o " + f.p("cal2"));
    REQUIRE(r2.exit_code == 0);
    for (const char* file : {"psf.tiff", "kernel.tiff", "report.pdf"})
        CHECK(test::slurp(f.dir / "cal" / file) == test::slurp(f.dir / "cal2" / file));
}

TEST_CASE("pinmask calibrate: bad input exits 2 and writes nothing") {
    Fixture f;
    write_tiff(f.dir / "flat.tiff", Image(Plane::Constant(300, 300, 0.5)), SampleFormat::kFloat32);
    write_tiff(f.dir / "tiny.tiff", Image(Plane::Constant(40, 40, 0.5)), SampleFormat::kFloat32);
    const std::pair<std::string, std::string> cases[] = {
        {"calibrate " + f.p("flat.tiff") + " --mask " + f.p("m.mask.json") + " -o " + f.p("o1"),
         "no spots found"},
        {"calibrate " + f.p("tiny.tiff") + " --mask " + f.p("m.mask.json") + " -o " + f.p("o2"),
         "smaller than one period"},
        {"calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") + " -o " + f.p("o3") +
             " --max-rotation 0.2",
         "max-rotation"},
        {"calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") + " -o " + f.p("o4") +
             " --saturation 100",
         "saturation over most spots"},
        {"calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") + " -o " + f.p("o5") +
             " --max-rotation -1",
         "--max-rotation = -1"},
        {"calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") + " -o " +
             f.p("point.tiff"),
         "-o"},
    };
    int i = 0;
    for (const auto& c : cases) {
        const std::string& args = c.first;  // named: CAPTURE's lambda captures it
        const std::string& expect = c.second;
        ++i;
        CAPTURE(args);
        const auto r = test::run_cli(args);
        CHECK(r.exit_code == 2);
        CHECK(r.err.find(expect) != std::string::npos);
        CHECK(!fs::exists(f.dir / ("o" + std::to_string(i))));
        CHECK(!fs::exists(f.dir / ("o" + std::to_string(i) + ".tmp-calibrate")));
    }
}

TEST_CASE(
    "pinmask calibrate --camera: a camera file replaces the mask's camera; flags beside it win") {
    Fixture f;
    // The paper camera at another wavelength, written by design --save-camera.
    const auto d = test::run_cli("design --preset paper --wavelength 633nm --save-camera " +
                                 f.p("he-ne.camera.json"));
    REQUIRE_MESSAGE(d.exit_code == 0, d.err);
    const auto r =
        test::run_cli("calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") +
                      " --camera " + f.p("he-ne.camera.json") + " -o " + f.p("cal"));
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    const Mask cal = io::read_mask_file(f.dir / "cal" / "calibrated.mask.json");
    CHECK(cal.camera.wavelength_m == doctest::Approx(633e-9));
    const auto r2 = test::run_cli("calibrate " + f.p("point.tiff") + " --mask " +
                                  f.p("m.mask.json") + " --camera " + f.p("he-ne.camera.json") +
                                  " --wavelength 532nm -o " + f.p("cal2"));
    REQUIRE_MESSAGE(r2.exit_code == 0, r2.err);
    CHECK(io::read_mask_file(f.dir / "cal2" / "calibrated.mask.json").camera.wavelength_m ==
          doctest::Approx(532e-9));
    const auto bad =
        test::run_cli("calibrate " + f.p("point.tiff") + " --mask " + f.p("m.mask.json") +
                      " --camera " + f.p("missing.camera.json") + " -o " + f.p("cal3"));
    CHECK(bad.exit_code == 2);
    CHECK(!fs::exists(f.dir / "cal3"));
}
