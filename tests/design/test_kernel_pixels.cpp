// Pixel integration of the 1-D profiles against independent long double references.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>

#include "core/errors/error.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_profile.hpp"
#include "tests/design/test_kernel_reference.hpp"
#include "tests/support/close.hpp"

using namespace pinmask;
using pinmask::test::kLdPi;
using pinmask::test::ld_integrate;
using pinmask::test::reference_profile;

namespace {

// Pixel integrals of profiles bounded by 1 over pixels of width <= a few units of v: the
// 12-point panels are exact to ~1e-19 and the sums round a few times.
constexpr double kPixelTol = 1e-14;
// Box overlaps are a subtraction and a division each.
constexpr double kBoxTol = 1e-15;

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// The pixel's interval in v for pixel index origin + k, centre at ppc/2.
std::pair<double, double> pixel_interval(const PixelProfile& p, std::size_t k, int ppc,
                                         double pixel_v) {
    const double x0 = p.origin + static_cast<double>(k) - 0.5 * ppc;
    return {x0 * pixel_v, (x0 + 1) * pixel_v};
}

double reference_sinc2(double a, double b) {
    const long long panels = static_cast<long long>(4 * (b - a)) + 4;
    return static_cast<double>(ld_integrate<long double>(a, b, panels, [](long double v) {
        if (v == 0) return 1.0L;
        const long double s = std::sin(kLdPi * v) / (kLdPi * v);
        return s * s;
    }));
}

}  // namespace

TEST_CASE("box: exact overlaps, centred, even and odd ppc, a point spot") {
    const KernelOptions o;
    const PixelProfile even = box_pixel_profile(7.94, 8, o);
    REQUIRE(even.values.size() == 8);
    CHECK(even.origin == 0);
    CHECK(std::fabs(even.values[0] - (0.97 / 7.94)) <= kBoxTol);
    CHECK(std::fabs(even.values[3] - (1 / 7.94)) <= kBoxTol);
    CHECK(even.values[0] == even.values[7]);
    CHECK(std::fabs(sum(even.values) - 1) <= kBoxTol);
    const PixelProfile odd = box_pixel_profile(3.2, 7, o);  // [1.9, 5.1]
    REQUIRE(odd.values.size() == 5);
    CHECK(odd.origin == 1);
    CHECK(std::fabs(odd.values[0] - 0.1 / 3.2) <= kBoxTol);
    CHECK(std::fabs(odd.values[2] - 1 / 3.2) <= kBoxTol);
    const PixelProfile point_even = box_pixel_profile(0.0, 8, o);
    CHECK(point_even.origin == 3);
    CHECK(point_even.values == std::vector<double>{0.5, 0.5});
    const PixelProfile point_odd = box_pixel_profile(0.0, 1, o);
    CHECK(point_odd.origin == 0);
    CHECK(point_odd.values == std::vector<double>{1.0});
    // A spot wider than the cap keeps the centre and says so.
    const PixelProfile capped = box_pixel_profile(100.0, 8, KernelOptions{0.999, 20});
    CHECK(capped.capped);
    CHECK(capped.values.size() == 20);
    CHECK(2 * capped.origin + 20 == 8);
    CHECK(std::fabs(capped.enclosed - 0.2) <= kBoxTol);
    CHECK_THROWS_AS(box_pixel_profile(-1.0, 8, o), InvalidInput);
    CHECK_THROWS_AS(box_pixel_profile(1.0, 0, o), InvalidInput);
}

TEST_CASE("box at a fractional centre: hand-computed overlaps, a point, the cap, refusals") {
    const KernelOptions o;
    // Side 3.5 centred at 10.3: [8.55, 12.05] covers pixels 8..12 by 0.45, 1, 1, 1, 0.05.
    const PixelProfile p = box_pixel_profile_at(3.5, 10.3, o);
    REQUIRE(p.values.size() == 5);
    CHECK(p.origin == 8);
    const double expected[5] = {0.45, 1.0, 1.0, 1.0, 0.05};
    for (int k = 0; k < 5; ++k) CHECK(std::fabs(p.values[k] - expected[k] / 3.5) <= kBoxTol);
    CHECK(std::fabs(sum(p.values) - 1) <= kBoxTol);
    CHECK(!p.capped);
    // Whole-pixel edges give no empty end pixels: side 2 centred at 5 covers pixels 4 and 5.
    const PixelProfile whole = box_pixel_profile_at(2.0, 5.0, o);
    CHECK(whole.origin == 4);
    CHECK(whole.values == std::vector<double>{0.5, 0.5});
    // Negative coordinates (a spot left of the window): side 1 at -0.25 covers [-0.75, 0.25].
    const PixelProfile left = box_pixel_profile_at(1.0, -0.25, o);
    CHECK(left.origin == -1);
    CHECK(std::fabs(left.values[0] - 0.75) <= kBoxTol);
    CHECK(std::fabs(left.values[1] - 0.25) <= kBoxTol);
    // A point: its pixel, or split over the two pixels sharing the edge it sits on.
    CHECK(box_pixel_profile_at(0.0, 3.7, o).values == std::vector<double>{1.0});
    CHECK(box_pixel_profile_at(0.0, 3.7, o).origin == 3);
    CHECK(box_pixel_profile_at(0.0, 4.0, o).values == std::vector<double>{0.5, 0.5});
    CHECK(box_pixel_profile_at(0.0, 4.0, o).origin == 3);
    // The integer kernel's placement (centre ppc/2 of the cell) gives the integer kernel.
    const PixelProfile centred = box_pixel_profile_at(7.94, 4.0, o);
    const PixelProfile integer = box_pixel_profile(7.94, 8, o);
    CHECK(centred.origin == integer.origin);
    REQUIRE(centred.values.size() == integer.values.size());
    for (std::size_t k = 0; k < centred.values.size(); ++k) {
        CHECK(std::fabs(centred.values[k] - integer.values[k]) <= kBoxTol);
    }
    // A spot wider than the cap keeps the cap's pixels around the centre's pixel.
    const PixelProfile capped = box_pixel_profile_at(100.0, 50.5, KernelOptions{0.999, 21});
    CHECK(capped.capped);
    CHECK(capped.values.size() == 21);
    CHECK(capped.origin == 40);
    CHECK(std::fabs(capped.enclosed - 0.21) <= kBoxTol);
    CHECK_THROWS_AS(box_pixel_profile_at(-1.0, 0.0, o), InvalidInput);
    CHECK_THROWS_AS(box_pixel_profile_at(1.0, NAN, o), InvalidInput);
}

TEST_CASE("sinc^2 pixel integrals match the reference for odd, even, prime ppc and pixel sizes") {
    for (int ppc : {1, 2, 7, 8, 13}) {
        for (double pixel_v : {0.05, 0.436, 1.0, 3.7}) {
            const KernelOptions o{0.99, 301};
            const PixelProfile p = diffraction_pixel_profile(fraunhofer_profile, pixel_v, ppc, o);
            INFO("ppc = " << ppc << " pixel_v = " << pixel_v);
            CHECK(2 * p.origin + static_cast<int>(p.values.size()) == ppc);  // centred at ppc/2
            for (std::size_t k = 0; k < p.values.size(); k += 1 + p.values.size() / 7) {
                const auto [a, b] = pixel_interval(p, k, ppc, pixel_v);
                CHECK(std::fabs(p.values[k] - reference_sinc2(a, b)) <= kPixelTol);
            }
            CHECK(std::fabs(p.enclosed - sum(p.values)) <= kPixelTol);
            if (!p.capped) {
                CHECK(p.enclosed >= 0.99);
                // Minimal: one pair fewer would not have reached the fraction.
                const double smaller = p.enclosed - 2 * p.values.front();
                CHECK((smaller < 0.99 || p.values.size() <= 2));
            } else {
                CHECK(static_cast<int>(p.values.size()) >= 300);
            }
        }
    }
}

TEST_CASE("Fresnel pixel integrals match the brute-force profile, paper-like and large N") {
    for (double n : {0.0, 0.881, 3.0, 12.0}) {
        const FresnelProfile h(n);
        const double pixel_v = 0.436;
        const PixelProfile p = diffraction_pixel_profile([&](double v) { return h(v); }, pixel_v, 8,
                                                         KernelOptions{0.99, 401});
        const std::size_t mid = p.values.size() / 2;
        for (std::size_t k : {mid, mid + 3, p.values.size() - 1}) {
            const auto [a, b] = pixel_interval(p, k, 8, pixel_v);
            const double ref = static_cast<double>(ld_integrate<long double>(
                a, b, 2, [&](long double v) { return reference_profile(n, double(v)); }));
            INFO("N = " << n << " k = " << k);
            CHECK(std::fabs(p.values[k] - ref) <= 1e-13);
        }
    }
}

TEST_CASE("the cap bounds the sinc^2 support and reports the kept energy") {
    const PixelProfile p =
        diffraction_pixel_profile(fraunhofer_profile, 0.01, 8, KernelOptions{0.999, 64});
    CHECK(p.capped);
    CHECK(p.values.size() == 64);
    // Kept: int_{-0.32}^{0.32} sinc^2.
    CHECK(std::fabs(p.enclosed - reference_sinc2(-0.32, 0.32)) <= kPixelTol);
}

TEST_CASE("work bound: pixels spanning millions of fringes are refused, not ground through") {
    CHECK_THROWS_AS(diffraction_pixel_profile(fraunhofer_profile, 1e8, 8, KernelOptions{}),
                    InvalidInput);
    CHECK_THROWS_AS(diffraction_pixel_profile(fraunhofer_profile, 0.0, 8, KernelOptions{}),
                    InvalidInput);
    CHECK_THROWS_AS(diffraction_pixel_profile(fraunhofer_profile, 1.0, 8, KernelOptions{0.0, 9}),
                    InvalidInput);
    CHECK_THROWS_AS(diffraction_pixel_profile(fraunhofer_profile, 1.0, 8, KernelOptions{0.9, 0}),
                    InvalidInput);
}
