// Independent high-accuracy references for the kernel tests: Gauss-Legendre nodes computed in
// long double (80-bit) and composite quadrature with them. Nothing here is shared with the code
// under test.
#pragma once

#include <cmath>
#include <complex>
#include <vector>

namespace pinmask::test {

struct LdRule {
    std::vector<long double> x, w;
};

inline LdRule ld_gauss_legendre(int m) {
    LdRule r;
    r.x.resize(m);
    r.w.resize(m);
    const long double pi = 3.141592653589793238462643383279502884L;
    for (int i = 0; i < m; ++i) {
        long double x = std::cos(pi * (i + 0.75L) / (m + 0.5L)), dp = 1;
        for (int it = 0; it < 60; ++it) {
            long double p0 = 1, p1 = x;
            for (int k = 2; k <= m; ++k) {
                const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = m * (x * p1 - p0) / (x * x - 1);
            const long double dx = p1 / dp;
            x -= dx;
            if (std::fabs(dx) < 1e-19L) break;
        }
        r.x[i] = x;
        r.w[i] = 2 / ((1 - x * x) * dp * dp);
    }
    return r;
}

// int_a^b fn over `panels` equal panels with a 20-point long double rule.
template <class T, class Fn>
T ld_integrate(long double a, long double b, long long panels, Fn&& fn) {
    static const LdRule rule = ld_gauss_legendre(20);
    const long double h = (b - a) / panels;
    T total{};
    for (long long p = 0; p < panels; ++p) {
        const long double mid = a + (p + 0.5L) * h;
        T s{};
        for (int i = 0; i < 20; ++i) s += rule.w[i] * fn(mid + 0.5L * h * rule.x[i]);
        total += s * (0.5L * h);
    }
    return total;
}

inline constexpr long double kLdPi = 3.141592653589793238462643383279502884L;

// h(N, v) = |J|^2 / 4 with J = int_{-1}^{1} exp(i pi (N s^2 - v s)) ds by brute force: panels
// small enough that the phase turns by at most ~1 radian across each.
inline double reference_profile(double n, double v) {
    const long double total_phase = 2 * kLdPi * (2 * std::fabs(n) + std::fabs(v));
    const long long panels = static_cast<long long>(total_phase) + 4;
    using C = std::complex<long double>;
    const C j = ld_integrate<C>(-1.0L, 1.0L, panels, [&](long double s) {
        const long double ph = kLdPi * (n * s * s - v * s);
        return C(std::cos(ph), std::sin(ph));
    });
    return static_cast<double>(std::norm(j) / 4);
}

}  // namespace pinmask::test
