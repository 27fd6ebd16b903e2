// optimize/simulate/simulate in float32: the float convolutions against the double ones
// and a direct sum, captures of any magnitude, the auto rule, byte-identical double output and
// results independent of the FFT thread count.
#include <doctest/doctest.h>

#include <cmath>

#include "core/fft/fft.hpp"
#include "decode/solvers/precision.hpp"
#include "optimize/simulate/simulate.hpp"
#include "tests/support/direct_cyclic.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
using pinmask::test::direct_cyclic;
using pinmask::test::random_plane;

namespace {

// float32 convolution against double, relative l2: the scaled inputs are rounded to float
// (6e-8 relative each), each of the three transforms adds ~6e-8 log2 N in l2 (Parseval, random
// rounding), N <= 2^18 here: ~3e-6 at worst; measured 8e-8 (cyclic, 17 x 12 and 256 x 256)
// and 1.4e-7 (linear, 230 x 330 grid) on these non-negative scenes. 5e-6 leaves a 35x margin
// and still catches a float/double mix-up (>= 1e-3).
constexpr double kSingleConvTol = 5e-6;

double rel_l2(const Plane& a, const Plane& b) {
    return std::sqrt((a - b).square().sum() / std::max(b.square().sum(), 1e-300));
}

}  // namespace

TEST_CASE("float32 cyclic capture: the direct sum (17 x 12) and double (256 x 256)") {
    const Plane x = random_plane(17, 12, 1), a = random_plane(17, 12, 2);
    const Plane single = cyclic_capture(x, a, true);
    CHECK(rel_l2(single, direct_cyclic(x, a)) <= kSingleConvTol);
    const Plane xl = random_plane(256, 256, 3), al = random_plane(256, 256, 4);
    const Plane d = cyclic_capture(xl, al), s = cyclic_capture(xl, al, true);
    CHECK(rel_l2(s, d) <= kSingleConvTol);
    CHECK(rel_l2(s, d) > 0.0);  // it really ran in float
}

TEST_CASE("float32 linear capture agrees with double (exact-geometry window)") {
    const Plane x = random_plane(31, 31, 5), w = random_plane(200, 300, 6);
    const Plane d = linear_capture(x, w), s = linear_capture(x, w, true);
    CHECK(rel_l2(s, d) <= kSingleConvTol);
    CHECK(rel_l2(s, d) > 0.0);
}

TEST_CASE("float32 capture of scenes far outside float's range: finite and to scale") {
    // 1e300 and 1e-300 overflow and underflow float32; the float path scales them to <= 1 first.
    const Plane x = random_plane(64, 64, 7), a = random_plane(64, 64, 8);
    const Plane ref = cyclic_capture(x, a, true);
    for (double k : {1e300, 1e-300, 3e38}) {
        const Plane s = cyclic_capture(x * k, a, true);
        INFO("scale " << k);
        REQUIRE(is_all_finite(s));
        CHECK(rel_l2(s / k, ref) <= kSingleConvTol);
    }
    // A PSF whose values cancel (sum|a| / sum a = 2e40): scaled by sum|a|, still finite.
    Plane cancel(1, 3), row(1, 3);
    cancel << 1e40, -1e40, 1.0;
    row << 0.5, 1.0, 0.25;
    CHECK(is_all_finite(cyclic_capture(row, cancel, true)));
}

TEST_CASE("simulate_capture: auto is float32 from 256 x 256 only; double is the default bytes") {
    CHECK(simulate_in_single(Precision::kAuto, 256, 256));
    CHECK_FALSE(simulate_in_single(Precision::kAuto, 255, 256));
    CHECK(simulate_in_single(Precision::kSingle, 8, 8));
    CHECK_FALSE(simulate_in_single(Precision::kDouble, 4096, 4096));
    const Image scene(random_plane(64, 64, 10));
    const Plane psf = random_plane(64, 64, 11);
    SimulationOptions o;
    o.noise.kind = NoiseKind::kGaussianSnr;
    o.noise.snr_db = 30.0;
    const SimulatedCapture def = simulate_capture(scene, psf, 10, 100, o);
    o.precision = Precision::kAuto;  // 64 x 64 < 256 x 256: double, the same bytes
    const SimulatedCapture autod = simulate_capture(scene, psf, 10, 100, o);
    CHECK((autod.capture.channels[0] == def.capture.channels[0]).all());
    o.precision = Precision::kSingle;
    const SimulatedCapture s = simulate_capture(scene, psf, 10, 100, o);
    // Same seed, same draws: the noisy captures differ by the clean captures' rounding (the
    // noise's sigma, set from mean(c^2), moves by the same relative amount).
    CHECK(rel_l2(s.clean.channels[0], def.clean.channels[0]) <= kSingleConvTol);
    CHECK(rel_l2(s.capture.channels[0], def.capture.channels[0]) <= kSingleConvTol);
}

TEST_CASE("float32 simulate does not depend on the FFT thread count (512 x 512)") {
    const Plane x = random_plane(512, 512, 12), a = random_plane(512, 512, 13);
    set_fft_threads(1);
    const Plane one = cyclic_capture(x, a, true);
    set_fft_threads(2);
    const Plane two = cyclic_capture(x, a, true);
    set_fft_threads(1);
    CHECK((one == two).all());
}
