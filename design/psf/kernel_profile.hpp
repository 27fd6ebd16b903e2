// The continuous 1-D intensity profile of one square pinhole behind the lens, on the sensor.
// Notation, once for the kernel files (docs/design.md section 2; lengths in metres):
//   d pinhole side, f lens-to-sensor distance, f' lens focal length, u object distance,
//   lambda wavelength, x sensor coordinate, w pixel pitch.
//   1/z_eff(u) = 1/f - 1/f' + 1/u: a point source at u seen through the thin lens f' is, behind
//     one pinhole, free-space Fresnel diffraction at distance z_eff, magnified by M = f / z_eff
//     = 1 - f/f' + f/u (z_eff infinite: Fraunhofer; negative: past focus).
//   N = d^2 |1/z_eff| / (4 lambda): the Fresnel number with the lens (0 when z_eff is infinite).
//   v = d x / (lambda f): the dimensionless sensor coordinate (Fraunhofer zeros at integer v).
// The amplitude on the sensor is, up to a phase,
//   A(x) ~ int_{-d/2}^{d/2} exp(i pi xi^2 / (lambda z_eff)) exp(-2 pi i xi x / (lambda f)) dxi,
// and with xi = s d / 2 the intensity per unit v, normalised by Parseval to int h dv = 1, is
//   h(N, v) = |J(N, v)|^2 / 4,   J(N, v) = int_{-1}^{1} exp(i pi (N s^2 - v s)) ds.
// A square pinhole's 2-D profile is h(N, v_x) h(N, v_y). Facts the kernel code relies on:
//   - h depends on |N| only (past focus mirrors before focus) and is even in v;
//   - N = 0 gives sinc^2(v), the Fraunhofer pattern; N -> inf gives the geometric box of height
//     1/(4N) on |v| < 2N, i.e. a spot of side |M| d on the sensor;
//   - h is band-limited: its spectrum in v lies within 1 cycle per unit v (J's lies within 1/2),
//     so Gauss-Legendre panels no wider than 1/2 integrate it to rounding.
#pragma once

#include <complex>
#include <vector>

namespace pinmask {

// At and below this |N| FresnelProfile uses the integral form, above it the closed form; both are
// accurate on either side (tests compare them on 0.05 <= N <= 4), the switch only picks the
// cheaper and better-conditioned one.
inline constexpr double kFresnelFormSwitch = 1.0;
// The integral form's Legendre expansion is built for |N| up to this.
inline constexpr double kIntegralFormMaxN = 4.0;

// sinc^2(v) = (sin(pi v) / (pi v))^2, the N = 0 profile.
double fraunhofer_profile(double v);

// h(N, v) for one Fresnel number.
class FresnelProfile {
  public:
    // Any finite N; the sign is irrelevant (see above). Throws InvalidInput for NaN/inf.
    explicit FresnelProfile(double fresnel_number);

    double fresnel_number() const { return n_; }

    // h(N, v), by the integral form when N <= kFresnelFormSwitch, else by the closed form.
    double operator()(double v) const;

    // Integral form ("stable at small N"): exp(i pi N s^2) is smooth for small N, so it is
    // projected onto Legendre polynomials with Gauss-Legendre quadrature, and each term is
    // integrated against exp(-i pi v s) exactly: int P_l(s) exp(-i a s) ds = 2 (-i)^l j_l(a).
    // No cancellation for any v, exact at N = 0. Requires N <= kIntegralFormMaxN.
    double integral_form(double v) const;

    // Closed form with Fresnel integrals: J = (F(t2) - F(t1)) / sqrt(2N) with t = (v -+ 2N) /
    // sqrt(2N). In the geometric shadow (|v| > 2N) both arguments are large and close when N is
    // small; there the difference is formed from the auxiliary function G with the exactly known
    // phase difference pi (t2^2 - t1^2) / 2 = 2 pi v, so no digits cancel. Requires N > 0.
    double closed_form(double v) const;

  private:
    double n_;
    std::vector<std::complex<double>> coeffs_;  // a_k = 2 (-1)^k c_{2k}: J = sum a_k j_{2k}(pi v)
};

// j_0(x) .. j_{l_max}(x), spherical Bessel functions of the first kind, x >= 0: upward recurrence
// from the closed forms of j_0, j_1 when x > l_max (stable there), else Miller's downward
// recurrence normalised by whichever of j_0, j_1 is larger.
std::vector<double> spherical_bessel_j(int l_max, double x);

}  // namespace pinmask
