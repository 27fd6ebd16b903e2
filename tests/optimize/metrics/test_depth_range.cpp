// optimize/metrics/depth_fisher's range and noise of the depth group (score --metrics depth): the
// distances equally spaced in 1/u, the default range around the working distance, the photon
// model's point source, and the refusals naming their fields. Checked against closed forms.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "design/optics/camera.hpp"
#include "design/pattern/mask.hpp"
#include "optimize/metrics/depth_fisher.hpp"

using namespace pinmask;

namespace {

Mask paper_mask() {
    Mask m;
    m.camera = paper_camera();  // f' = 120 mm, u = 6 m
    m.pattern.n = 16;
    return m;
}

std::string refusal(const Mask& m, const DepthRange& r) {
    try {
        depth_samples(m, r);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("depth range: samples equally spaced in 1/u, ends exact; default u/2 .. 2u") {
    const Mask m = paper_mask();
    DepthRange r;
    r.from_m = 0.4;
    r.to_m = 2.0;
    const auto u = depth_samples(m, r);
    REQUIRE(u.size() == 3);
    CHECK(u[0] == 0.4);
    CHECK(u[2] == 2.0);
    CHECK(1.0 / u[1] == doctest::Approx((1.0 / 0.4 + 1.0 / 2.0) / 2.0).epsilon(1e-14));
    r.samples = 5;
    const auto u5 = depth_samples(m, r);
    for (int i = 0; i < 5; ++i)
        CHECK(1.0 / u5[i] == doctest::Approx(2.5 - i * (2.5 - 0.5) / 4.0).epsilon(1e-14));
    const auto d = depth_samples(m, DepthRange{});
    REQUIRE(d.size() == 3);
    CHECK(d[0] == 3.0);
    CHECK(d[2] == 12.0);
    CHECK(d[1] == doctest::Approx(1.0 / ((1.0 / 3.0 + 1.0 / 12.0) / 2.0)));
    r = {};
    r.from_m = r.to_m = 5.0;
    CHECK(depth_samples(m, r).size() == 1);
}

TEST_CASE("depth range: refusals name depth_from_m / depth_to_m") {
    Mask m = paper_mask();
    DepthRange r;
    r.from_m = -1.0;
    r.to_m = 2.0;
    CHECK(refusal(m, r).find("`depth_from_m`") != std::string::npos);
    r.from_m = 3.0;
    CHECK(refusal(m, r).find("`depth_to_m`") != std::string::npos);  // to < from
    r.from_m = 1.0;
    r.to_m = 0.0;  // one end only
    CHECK(refusal(m, r).find("`depth_to_m`") != std::string::npos);
    r.from_m = 0.1;  // inside f' = 120 mm
    r.to_m = 2.0;
    CHECK(refusal(m, r).find("`depth_from_m`") != std::string::npos);
    r.from_m = std::numeric_limits<double>::quiet_NaN();
    CHECK(refusal(m, r).find("`depth_from_m` = nan") != std::string::npos);
    m.camera.object_distance_m = std::numeric_limits<double>::infinity();  // no default range
    CHECK(refusal(m, DepthRange{}).find("`depth_from_m`") != std::string::npos);
}

TEST_CASE("depth noise: the photon model's point source is ppp K electrons; read, dark, ADC add") {
    NoiseModel n;
    n.kind = NoiseKind::kPhoton;
    n.photons_per_pinhole = 250.0;
    n.read_noise_e = 3.0;
    n.dark_current_e = 7.0;
    n.full_well_e = 1023.0;
    n.adc_bits = 10;  // q = 1 e
    const DepthFisherOptions o = depth_fisher_noise(n, 20);
    CHECK(o.photons == 5000.0);
    CHECK(o.read_noise_e == doctest::Approx(std::sqrt(9.0 + 7.0 + 1.0 / 12.0)).epsilon(1e-15));
    n.kind = NoiseKind::kGaussianSnr;
    CHECK_THROWS_AS(depth_fisher_noise(n, 20), InvalidInput);
}
