// Stiff and extreme physics: Fresnel numbers from 1e-4 to 1e4, the sensor approaching the focal
// plane (f -> f', and f = f' exactly), the object approaching the sensor distance (u -> f), tiny
// and huge pixel pitches. For every case: the optics report has no NaN (infinite only where
// design/optics/optics documents it), the kernel is finite and sums to 1 (or is refused with
// InvalidInput naming the quantity), and every model used outside its accurate range, and every
// support that loses more than 1 % of the energy, is said by design/psf/kernel_validity.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "design/optics/camera.hpp"
#include "design/optics/optics.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/kernel_validity.hpp"

using namespace pinmask;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Normalisation tolerance: a sum of at most 1025^2 doubles each < 1 (rounding ~ 1e-16 each).
constexpr double kSumTolerance = 1e-9;

bool sanitized() { return std::getenv("PINMASK_SANITIZED") != nullptr; }

// A lensless camera (f' = inf, u = inf) whose Fresnel number N = d^2 / (4 lambda f) is `n`.
// Below N = 1e-2 the pinhole shrinks with sqrt(N) (to 80 wavelengths at 1e-4) so f stays at
// 8.8 m, inside the largest lens-to-sensor distance validate accepts (10 m).
Camera camera_with_fresnel_number(double n) {
    Camera c = paper_camera();
    c.lens_focal_m = kInf;
    c.object_distance_m = kInf;
    if (n < 1e-2) c.pinhole_m *= std::sqrt(n / 1e-2);
    c.sensor_distance_m = c.pinhole_m * c.pinhole_m / (4.0 * c.wavelength_m * n);
    return c;
}

void check_report_has_no_nan(const Camera& c) {
    const OpticsReport r = compute_optics(c, {16, 20, 2, 2});
    for (double v :
         {r.magnification, r.magnification_at_u, r.geometric_spot_m, r.geometric_spot_at_u_m,
          r.pixels_per_cell_at_inf, r.pixels_per_cell_at_u, r.pinhole_for_integer_pixels_m,
          r.optimum_pinhole_m, r.fresnel_number, r.effective_distance_m,
          r.effective_distance_at_u_m, r.fresnel_number_with_lens, r.fresnel_number_with_lens_at_u,
          r.lsi_min_object_distance_m, r.lsi_mismatch_px, r.periods_on_sensor_cols,
          r.periods_on_sensor_rows, r.mask_width_m, r.open_fraction}) {
        CHECK_FALSE(std::isnan(v));
    }
    CHECK(r.integer_pixels_per_cell >= 1);
}

// Builds the kernel of `model`; returns false when it was refused (InvalidInput, which must name
// what it refused). On success: finite, sum 1, kept energy in [0, 1], and the validity query
// warns exactly when more than 1 % of the energy was lost.
bool check_kernel(const Camera& c, const std::string& model, int ppc, double& energy) {
    KernelOptions ko;
    ko.max_width_px = sanitized() ? 65 : 257;
    Kernel k;
    try {
        k = make_kernel(c, KernelSpec{model, "", {}}, ppc, ko);
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()).size() > 10);
        return false;
    }
    CHECK(k.values.isFinite().all());
    CHECK(std::fabs(k.values.sum() - 1.0) < kSumTolerance);
    CHECK(k.enclosed_energy >= 0.0);
    CHECK(k.enclosed_energy <= 1.0 + 1e-12);
    energy = k.enclosed_energy;
    const KernelValidity v = kernel_validity(c, k.model, k.enclosed_energy);
    CHECK(v.energy_ok == (k.enclosed_energy >= 1.0 - kMaxKernelEnergyLoss));
    if (!v.energy_ok) CHECK_FALSE(v.ok());
    return true;
}

}  // namespace

TEST_CASE("Fresnel numbers 1e-4 .. 1e4: finite outputs, every out-of-range model said") {
    for (double n = 1e-4; n <= 1.0001e4; n *= 10.0) {
        CAPTURE(n);
        const Camera c = camera_with_fresnel_number(n);
        validate(c);
        CHECK(fresnel_number_at_u(c) == doctest::Approx(n).epsilon(1e-9));
        check_report_has_no_nan(c);
        const KernelValidity fraunhofer = kernel_validity(c, KernelModel::kFraunhofer);
        const KernelValidity box = kernel_validity(c, KernelModel::kBox);
        const KernelValidity fresnel = kernel_validity(c, KernelModel::kFresnel);
        CHECK(fraunhofer.model_accurate == (n <= kAutoFraunhoferMaxN));
        CHECK(box.model_accurate == (n >= kAutoBoxMinN));
        CHECK(fresnel.model_accurate);  // d >= 80 wavelengths: scalar optics hold
        CHECK(fraunhofer.ok() == fraunhofer.model_accurate);
        CHECK(box.ok() == box.model_accurate);
        if (!fraunhofer.ok()) CHECK(fraunhofer.warnings.front().find("fraunhofer") == 0);
        if (!box.ok()) CHECK(box.warnings.front().find("box") == 0);
        // auto always picks a model that is accurate where it is used.
        CHECK(kernel_validity(c, KernelModel::kAuto).model_accurate);
        double energy = 1.0;
        if (!sanitized() || n <= 1e-2 || n >= 1e2) {
            for (const char* model : {"auto", "box", "fraunhofer"}) {
                CAPTURE(model);
                check_kernel(c, model, 8, energy);
            }
        }
    }
}

TEST_CASE("the far field at N = 1e-4 loses energy from any support: the loss is said") {
    // sinc^2 at N = 1e-4 spreads the spot over ~1e4 cells: the capped support keeps a few %.
    const Camera c = camera_with_fresnel_number(1e-4);
    double energy = 1.0;
    REQUIRE(check_kernel(c, "fraunhofer", 8, energy));
    CHECK(energy < 0.5);
    const KernelValidity v = kernel_validity(c, KernelModel::kFraunhofer, energy);
    CHECK_FALSE(v.energy_ok);
    CHECK(v.warnings.back().find("% of its energy") != std::string::npos);
}

TEST_CASE("a wavelength beyond the pinhole is outside every model, 1e300 m included") {
    for (double lambda : {45e-6, 1e-3, 1.0, 1e300}) {
        CAPTURE(lambda);
        Camera c = paper_camera();
        c.wavelength_m = lambda;
        if (lambda > 100e-6) {
            // Beyond any design wavelength: validate refuses it, naming the field and the
            // range; the query still says no model holds (it is asked before validation by
            // nobody, but must not call such a wavelength "far field, accurate").
            CHECK_THROWS_WITH_AS(validate(c), doctest::Contains("wavelength_m"), InvalidInput);
        } else {
            validate(c);
            check_report_has_no_nan(c);
        }
        for (KernelModel m :
             {KernelModel::kAuto, KernelModel::kFraunhofer, KernelModel::kFresnel}) {
            const KernelValidity v = kernel_validity(c, m);
            CHECK_FALSE(v.model_accurate);
            REQUIRE_FALSE(v.warnings.empty());
            CHECK(v.warnings.front().find("wavelengths wide") != std::string::npos);
        }
    }
    Camera ok = paper_camera();
    ok.wavelength_m = 43e-6;  // d = 10.2 wavelengths: inside
    CHECK(kernel_validity(ok, KernelModel::kFresnel).ok());
}

TEST_CASE("f -> f' and f = f': the Fraunhofer limit, finite kernels, M = 0 said") {
    for (double rel : {1e-2, 1e-4, 1e-6, 1e-9, 0.0, -1e-9, -1e-6, -1e-2}) {
        CAPTURE(rel);
        Camera c = paper_camera();
        c.object_distance_m = kInf;
        c.sensor_distance_m = c.lens_focal_m * (1.0 + rel);
        validate(c);
        check_report_has_no_nan(c);
        const KernelValidity v = kernel_validity(c, KernelModel::kAuto);
        CHECK(std::isfinite(v.fresnel_number));
        if (rel == 0.0) {
            CHECK(v.magnification == 0.0);
            CHECK(v.fresnel_number == 0.0);
            REQUIRE_FALSE(v.warnings.empty());
            CHECK(v.warnings.front().find("magnification") != std::string::npos);
        }
        double energy = 1.0;
        check_kernel(c, "auto", 8, energy);
    }
}

TEST_CASE("u -> f': the object just beyond the focal length keeps every output finite") {
    // Inside the focal length (at the sensor distance, or at f' itself) the lens forms no real
    // image: every command refuses the camera, naming the field.
    for (double u : {paper_camera().sensor_distance_m, paper_camera().lens_focal_m}) {
        Camera c = paper_camera();
        c.object_distance_m = u;
        CHECK_THROWS_WITH_AS(validate(c), doctest::Contains("inside the focal length"),
                             InvalidInput);
    }
    for (double rel : {1.0, 1e-2, 1e-4, 1e-8}) {
        CAPTURE(rel);
        Camera c = paper_camera();
        c.object_distance_m = c.lens_focal_m * (1.0 + rel);
        validate(c);
        check_report_has_no_nan(c);
        const KernelValidity v = kernel_validity(c, KernelModel::kAuto);
        CHECK(std::isfinite(v.fresnel_number));
        CHECK(std::isfinite(v.magnification));
        double energy = 1.0;
        check_kernel(c, "auto", 8, energy);
    }
}

TEST_CASE("tiny and huge pixel pitches: finite report and kernels, or refused naming why") {
    for (double w : {1e-9, 1e-7, 1e-5, 1e-3, 1e-1, 10.0}) {
        CAPTURE(w);
        Camera c = paper_camera();
        c.pixel_pitch_m = w;
        if (w > 1e-3) {
            // Larger than any sensor pixel: a unit left off (10 = 10 m), refused naming why.
            CHECK_THROWS_WITH_AS(validate(c), doctest::Contains("pixel_pitch_m"), InvalidInput);
            continue;
        }
        validate(c);
        check_report_has_no_nan(c);
        for (const char* model : {"auto", "box", "fresnel"}) {
            CAPTURE(model);
            double energy = 1.0;
            check_kernel(c, model, 8, energy);
        }
    }
}

TEST_CASE("a support that keeps 29 % of the kernel's energy is said, one keeping 99.5 % is not") {
    const Camera c = paper_camera();
    for (const auto& setting : {std::pair{0.54, true}, std::pair{0.9975, false}}) {
        const double per_axis = setting.first;  // named: CAPTURE's lambda captures it
        const bool warned = setting.second;
        CAPTURE(per_axis);
        KernelOptions ko;
        ko.energy_fraction = per_axis;  // the 2-D energy is about the square of it
        const Kernel k = make_kernel(c, KernelSpec{"fresnel", "", {}}, 8, ko);
        const KernelValidity v = kernel_validity(c, k.model, k.enclosed_energy);
        CHECK(v.energy_ok == !warned);
        CHECK(v.model_accurate);  // fresnel at the paper's N = 0.88
        if (warned) {
            CHECK(k.enclosed_energy < 0.35);
            REQUIRE_FALSE(v.warnings.empty());
            CHECK(v.warnings.back().find("% of its energy") != std::string::npos);
        }
    }
}
