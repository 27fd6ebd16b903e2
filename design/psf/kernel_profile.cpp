#include "design/psf/kernel_profile.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors/error.hpp"
#include "design/psf/fresnel_integrals.hpp"
#include "design/psf/kernel_quadrature.hpp"

namespace pinmask {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
// The Legendre expansion of exp(i pi N s^2) is cut where the Taylor term (pi N)^k / k! of the
// phase factor drops below this: far below double rounding of the O(1) result.
constexpr double kTaylorCut = 1e-18;
// Above this argument F(t) is formed from G (continued fraction / asymptotic), see fresnel_cs.
constexpr double kAuxMin = 1.5;
// Miller recurrence rescaling: keeps the unnormalised values far from overflow.
constexpr double kRescaleAbove = 1e200;

}  // namespace

double fraunhofer_profile(double v) {
    if (v == 0.0) return 1.0;
    const double r = v - 2.0 * std::round(0.5 * v);  // exact; sin(pi v) = sin(pi r)
    const double s = std::sin(kPi * r) / (kPi * v);
    return s * s;
}

std::vector<double> spherical_bessel_j(int l_max, double x) {
    if (l_max < 0 || !(x >= 0.0) || std::isinf(x)) {
        throw InvalidInput("spherical_bessel_j: need l_max >= 0 and finite x >= 0 (got l_max = " +
                           std::to_string(l_max) + ", x = " + std::to_string(x) + ")");
    }
    std::vector<double> j(static_cast<std::size_t>(l_max) + 1, 0.0);
    if (x == 0.0) {
        j[0] = 1.0;
        return j;
    }
    const double s = std::sin(x), c = std::cos(x);
    const double j0 = s / x;
    const double j1 = x < 1.0 ? 0.0 : s / (x * x) - c / x;  // only used for x >= 1
    if (x > l_max) {
        j[0] = j0;
        if (l_max >= 1) j[1] = s / (x * x) - c / x;
        for (int l = 1; l < l_max; ++l) j[l + 1] = (2 * l + 1) / x * j[l] - j[l - 1];
        return j;
    }
    // Miller: start far enough above l_max that the neglected solution is below rounding.
    const int start = l_max + 16 + static_cast<int>(std::sqrt(40.0 * (l_max + 1)));
    double jp = 0.0, jc = 1e-300;  // j_{l+1}, j_l (unnormalised)
    for (int l = start; l >= 1; --l) {
        const double jm = (2 * l + 1) / x * jc - jp;  // j_{l-1}
        jp = jc;
        jc = jm;
        if (l - 1 <= l_max) j[l - 1] = jc;
        if (l <= l_max) j[l] = jp;
        if (std::fabs(jc) > kRescaleAbove) {
            jc /= kRescaleAbove;
            jp /= kRescaleAbove;
            for (int k = std::max(l - 1, 0); k <= l_max; ++k) j[k] /= kRescaleAbove;
        }
    }
    const bool use_j0 = x < 1.0 || std::fabs(j0) >= std::fabs(j1);
    const double scale = use_j0 ? j0 / j[0] : j1 / j[1];
    for (double& v : j) v *= scale;
    return j;
}

FresnelProfile::FresnelProfile(double fresnel_number) : n_(std::fabs(fresnel_number)) {
    if (!std::isfinite(fresnel_number)) {
        throw invalid_field("Fresnel number", std::to_string(fresnel_number), "must be finite");
    }
    if (n_ > kIntegralFormMaxN) return;
    // Number of Taylor terms of exp(i pi N s^2) that matter, hence the Legendre degree.
    int k_terms = 0;
    for (double term = 1.0; term > kTaylorCut; ++k_terms) term *= kPi * n_ / (k_terms + 1);
    const int l_max = 2 * k_terms + 4;
    const GaussLegendreRule rule = gauss_legendre(l_max + 8);
    std::vector<Complex> c(static_cast<std::size_t>(l_max) + 1, 0.0);
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        const double s = rule.nodes[i];
        const Complex phi = cis_pi(n_ * s * s) * rule.weights[i];
        double p0 = 1.0, p1 = s;  // P_0, P_1
        c[0] += phi * p0;
        for (int l = 1; l <= l_max; ++l) {
            if (l >= 2) {
                const double p2 = ((2 * l - 1) * s * p1 - (l - 1) * p0) / l;
                p0 = p1;
                p1 = p2;
            }
            c[l] += phi * (l == 1 ? s : p1);
        }
    }
    coeffs_.reserve(l_max / 2 + 1);
    for (int l = 0; l <= l_max; l += 2) {
        const double sign = (l / 2) % 2 == 0 ? 1.0 : -1.0;
        coeffs_.push_back(c[l] * (0.5 * (2 * l + 1)) * (2.0 * sign));
    }
}

double FresnelProfile::operator()(double v) const {
    return n_ <= kFresnelFormSwitch ? integral_form(v) : closed_form(v);
}

double FresnelProfile::integral_form(double v) const {
    if (coeffs_.empty()) {
        throw InvalidInput("FresnelProfile::integral_form: N = " + std::to_string(n_) +
                           " is above " + std::to_string(kIntegralFormMaxN));
    }
    const int l_max = 2 * (static_cast<int>(coeffs_.size()) - 1);
    const std::vector<double> j = spherical_bessel_j(l_max, kPi * std::fabs(v));
    Complex total = 0.0;
    for (std::size_t k = 0; k < coeffs_.size(); ++k) total += coeffs_[k] * j[2 * k];
    return 0.25 * std::norm(total);
}

double FresnelProfile::closed_form(double v) const {
    if (!(n_ > 0.0)) throw InvalidInput("FresnelProfile::closed_form: needs N > 0");
    const double av = std::fabs(v);
    const double a = std::sqrt(2.0 * n_);
    const double t2 = (av + 2.0 * n_) / a;
    Complex diff;
    if (av <= 2.0 * n_) {
        // Inside the geometric spot: F(t2) + F(t1') with both arguments >= 0, no cancellation.
        diff = fresnel_cs(t2) + fresnel_cs((2.0 * n_ - av) / a);
    } else {
        const double t1 = (av - 2.0 * n_) / a;  // 0 < t1 < t2, t2 - t1 = 2a
        if (t1 >= kAuxMin) {
            // F(t2) - F(t1) = e^{i pi t1^2/2} [G(t1) - G(t2) e^{i pi (t2^2 - t1^2)/2}], and
            // (t2^2 - t1^2) / 2 = 2v exactly: only the modulus is needed.
            diff = fresnel_aux(t1) - fresnel_aux(t2) * cis_pi(2.0 * av);
        } else {
            diff = fresnel_cs(t2) - fresnel_cs(t1);
        }
    }
    return std::norm(diff) / (8.0 * n_);
}

}  // namespace pinmask
