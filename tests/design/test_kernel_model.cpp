#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "core/errors/error.hpp"
#include "design/psf/kernel_model.hpp"
#include "design/psf/kernel_profile.hpp"
#include "design/psf/kernel_quadrature.hpp"

using namespace pinmask;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// int |h_fresnel - h_model| dv over |v| <= V: the tail beyond V contributes at most 2/(pi^2 V)
// per profile (see test_kernel_profile), so V = 2N + 3000 bounds it by 1.4e-4.
double l1_distance(double n, bool against_box) {
    const FresnelProfile h(n);
    const auto rule = gauss_legendre(12);
    const double big_v = 2 * n + 3000;
    return 2 * integrate_panels(rule, 0.0, big_v, static_cast<int>(2 * big_v), [&](double v) {
               const double model =
                   against_box ? (v < 2 * n ? 1 / (4 * n) : 0.0) : fraunhofer_profile(v);
               return std::fabs(h(v) - model);
           });
}

// Tail bound of l1_distance (both profiles' tails beyond V, see above).
constexpr double kTailAllowance = 2 * 2 / (M_PI * M_PI * 3000);

}  // namespace

TEST_CASE("names round-trip; unknown names are InvalidInput listing the models") {
    for (auto m : {KernelModel::kAuto, KernelModel::kBox, KernelModel::kFraunhofer,
                   KernelModel::kFresnel, KernelModel::kPaperFig3b, KernelModel::kMeasured}) {
        CHECK(parse_kernel_model(kernel_model_name(m)) == m);
    }
    // The one table: every enumerator once, in the order help texts list them.
    CHECK(kernel_model_names() == "auto | box | fraunhofer | fresnel | paper-fig3b | measured");
    CHECK(name_list(kKernelModelNames).size() == 6);
    try {
        parse_kernel_model("gauss", "`kernel`");
        FAIL("accepted");
    } catch (const InvalidInput& e) {
        CHECK(contains(std::string(e.what()), "`kernel` = 'gauss'"));
        CHECK(contains(std::string(e.what()), "gauss"));
        CHECK(contains(std::string(e.what()), "fresnel"));
    }
}

TEST_CASE("auto picks by N with the documented bounds") {
    CHECK(choose_kernel_model(0.0).model == KernelModel::kFraunhofer);
    CHECK(choose_kernel_model(kAutoFraunhoferMaxN).model == KernelModel::kFraunhofer);
    CHECK(choose_kernel_model(kAutoFraunhoferMaxN * 1.001).model == KernelModel::kFresnel);
    CHECK(choose_kernel_model(0.87).model == KernelModel::kFresnel);
    CHECK_THROWS_AS(choose_kernel_model(-0.87), InvalidInput);  // N is a magnitude
    CHECK(choose_kernel_model(kAutoBoxMinN * 0.999).model == KernelModel::kFresnel);
    CHECK(choose_kernel_model(kAutoBoxMinN).model == KernelModel::kBox);
    CHECK(choose_kernel_model(1e9).model == KernelModel::kBox);
    CHECK(contains(choose_kernel_model(0.87).reason, "0.87"));
    CHECK_THROWS_AS(choose_kernel_model(NAN), InvalidInput);
}

TEST_CASE("at the auto bounds the simpler model is within the L1 target of the Fresnel profile") {
    const double fraunhofer = l1_distance(kAutoFraunhoferMaxN, false);
    const double box = l1_distance(kAutoBoxMinN, true);
    CHECK(fraunhofer <= kAutoL1Target + kTailAllowance);
    CHECK(box <= kAutoL1Target + kTailAllowance);
    // ...and the bounds are not needlessly conservative: just past them the error exceeds 80% of
    // the target.
    CHECK(l1_distance(kAutoFraunhoferMaxN * 1.1, false) > 0.8 * kAutoL1Target);
    CHECK(l1_distance(kAutoBoxMinN / 1.5, true) > 0.8 * kAutoL1Target);
}
