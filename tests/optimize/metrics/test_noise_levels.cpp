// optimize/metrics/noise_levels: the levels score, compare, search and the Python module ask for,
// the photon model's sensor stages, and the errors naming the command-line flag.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "optimize/metrics/noise_levels.hpp"

using namespace pinmask;

namespace {

std::string message_of(const NoiseLevelSettings& s) {
    try {
        noise_levels(s);
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("noise levels: Gaussian list, photon list with every sensor stage, the phrase") {
    NoiseLevelSettings g;
    g.snr_db = {20.0, 30.5};
    std::string text;
    const auto gl = noise_levels(g, &text);
    REQUIRE(gl.size() == 2);
    CHECK(gl[0].model.kind == NoiseKind::kGaussianSnr);
    CHECK(gl[1].model.snr_db == 30.5);
    CHECK(gl[0].key == noise_level(gl[0].model).key);
    CHECK(text == "Gaussian noise at SNR 20,30.5 dB");

    NoiseLevelSettings p;
    p.photons = {200.0, 2000.0};
    p.sensor.read_noise = 3.0;
    p.sensor.dark_current = 0.5;
    p.sensor.full_well = 30000.0;
    p.sensor.bits = 12;
    p.sensor.optical_density = 3.0;
    const auto pl = noise_levels(p, &text);
    REQUIRE(pl.size() == 2);
    const NoiseModel& m = pl[1].model;
    CHECK(m.kind == NoiseKind::kPhoton);
    CHECK(m.photons_per_pinhole == 2000.0);
    CHECK(m.read_noise_e == 3.0);
    CHECK(m.dark_current_e == 0.5);
    CHECK(m.full_well_e == 30000.0);
    CHECK(m.adc_bits == 12);
    CHECK(m.film_optical_density == 3.0);
    CHECK(text.rfind("the photon model at 200,2000 electrons", 0) == 0);
}

TEST_CASE("photon model: stages left out are absent, and listed as skipped") {
    std::vector<std::string> skipped;
    const NoiseModel m = photon_model(100.0, SensorSettings{}, &skipped);
    CHECK(m.read_noise_e == 0.0);
    CHECK(m.adc_bits == 0);
    CHECK(std::isinf(m.full_well_e));
    CHECK(std::isinf(m.film_optical_density));
    CHECK(skipped.size() == 5);
}

TEST_CASE("noise levels: bad settings name the flag") {
    NoiseLevelSettings s;
    s.snr_db = {};
    CHECK(message_of(s).find("`snr_db`") == 0);
    s.snr_db = std::vector<double>(kMaxNoiseLevels + 1, 30.0);
    CHECK(message_of(s).find("more than 64") != std::string::npos);
    s.snr_db = {30.0};
    s.sensor.dark_current = 1.0;
    CHECK(message_of(s).rfind("`dark_current`: a sensor parameter of the photon model", 0) == 0);
    s.photons = {100.0};
    s.sensor = {};
    s.sensor.bits = 8;
    CHECK(message_of(s).rfind("`bits`", 0) == 0);
    s.sensor = {};
    s.photons = {-5.0};
    CHECK(message_of(s).rfind("`photons` (photons_per_pinhole = ", 0) == 0);
    s.photons = {std::nan("")};
    CHECK(message_of(s).rfind("`photons`", 0) == 0);
    s.photons = {100.0};
    s.sensor.read_noise = -1.0;
    CHECK(message_of(s).rfind("`read_noise`", 0) == 0);
}
