// optimize/simulate/simulate_pipeline against a second path written here from the parts it composes
// (synthesize_psf, make_scene, simulate_capture), and its validate() rules.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "design/pattern/families.hpp"
#include "design/psf/psf.hpp"
#include "optimize/simulate/simulate_pipeline.hpp"

using namespace pinmask;

namespace {

Mask paper_mask() {
    Mask m;
    m.camera = paper_camera();
    std::mt19937_64 rng(5);
    m.pattern = paper_pattern(rng);
    m.psf.pixels_per_cell = 4;
    return m;
}

bool has_line(const std::vector<std::string>& lines, const std::string& start) {
    for (const auto& l : lines)
        if (l.rfind(start, 0) == 0) return true;
    return false;
}

}  // namespace

TEST_CASE("simulate pipeline: the capture equals simulate_capture on the mask's PSF and scene") {
    const Mask mask = paper_mask();
    for (NoiseKind kind : {NoiseKind::kNone, NoiseKind::kGaussianSnr, NoiseKind::kPhoton}) {
        SimulatePipelineOptions o;
        o.scene = scene_from_name("usaf");
        o.sim.noise.kind = kind;
        o.sim.noise.photons_per_pinhole = 200.0;
        o.sim.noise.dark_current_e = 3.0;
        o.sim.seed = 11;
        o.sim.full_sensor = true;
        o.sim.dark_frame = kind == NoiseKind::kPhoton;
        o.sensor = Size2{70, 50};
        const SimulatePipelineResult r = run_simulate_pipeline(mask, o);

        // Second path: the parts by hand.
        const Kernel kernel = mask_kernel(mask);
        const Plane psf = synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell);
        const int m = static_cast<int>(psf.rows());
        SimulationOptions sim = o.sim;
        sim.sensor_cols = 70;
        sim.sensor_rows = 50;
        const SimulatedCapture ref =
            simulate_capture(make_scene(o.scene, m, m), psf, 20, 16 * 16, sim);
        REQUIRE(r.capture.capture.n_channels() == ref.capture.n_channels());
        CHECK(r.capture.capture.rows() == 50);
        CHECK(r.capture.capture.cols() == 70);
        // Same inputs, same seed: bit-identical (nothing is recomputed differently).
        CHECK((r.capture.capture.channels[0].array() == ref.capture.channels[0].array()).all());
        if (o.sim.dark_frame)
            CHECK((r.capture.dark.channels[0].array() == ref.dark.channels[0].array()).all());
        CHECK(r.summary.period_px == m);
        CHECK(r.summary.holes == 20);
        CHECK(r.summary.scene_name == "usaf");
        CHECK(has_line(r.summary.explain, "full-sensor tiling: the period repeated over 70 x 50"));
        CHECK(has_line(r.summary.explain,
                       o.sim.dark_frame ? "dark frame: all-opaque" : "dark frame skipped"));
    }
}

TEST_CASE("simulate pipeline: exact geometry covers the window; validate names flag and rule") {
    const Mask mask = paper_mask();
    SimulatePipelineOptions o;
    o.sim.noise.kind = NoiseKind::kNone;
    o.exact_geometry = true;
    o.window = Size2{40, 30};  // typed ROWSxCOLS: 40 rows, 30 columns
    const SimulatePipelineResult r = run_simulate_pipeline(mask, o);
    CHECK(r.capture.capture.rows() == 40);
    CHECK(r.capture.capture.cols() == 30);
    CHECK(has_line(r.summary.explain, "geometry: exact at u = "));

    auto message = [&](const SimulatePipelineOptions& bad) {
        try {
            run_simulate_pipeline(mask, bad);
        } catch (const InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    SimulatePipelineOptions a;
    a.sensor = Size2{10, 10};
    CHECK(message(a).find("`sensor`") != std::string::npos);
    CHECK(message(a).find("only applies with `full_sensor`") != std::string::npos);
    SimulatePipelineOptions b;
    b.window = Size2{10, 10};
    CHECK(message(b).find("`window` = 10x10: only with `exact_geometry`") != std::string::npos);
    SimulatePipelineOptions c = o;
    c.sim.full_sensor = true;
    CHECK(message(c).find("`full_sensor`") != std::string::npos);
    SimulatePipelineOptions d;
    d.sim.dark_frame = true;  // the Gaussian model has no dark signal
    CHECK(message(d).find("dark_frame") != std::string::npos);
}
