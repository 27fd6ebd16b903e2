#include "decode/calibrate/lattice_fft.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "decode/calibrate/spots.hpp"

namespace pinmask::calibrate {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// A step of the search moves the highest harmonic in use by this many frequency bins.
constexpr double kStepBins = 0.4;
// Frequencies whose ring mean exceeds the noise floor by this factor are usable.
constexpr double kSignalOverNoise = 4.0;
// Rings at least this far out (cycles per pixel) hold only noise for the floor's estimate.
constexpr double kNoiseRing = 0.4;
// The first level uses harmonics up to this many period fundamentals and at least this many
// frequency bins (the window's main lobe around DC is excluded below kDcBins).
constexpr double kFirstHarmonics = 3.0, kFirstBins = 6.0, kDcBins = 2.5;
// Highest frequency used, in units of the cell lattice's fundamental (1 / pitch).
constexpr double kMaxCellHarmonic = 1.5;
constexpr int kMaxBinsPerCell = 8;
// The fold's refinement uses about this many pixels (a stride over rows and columns) and stops
// when a step moves the frame's far edge by less than this many cells.
constexpr double kFoldPixels = 250000.0, kFinestStepCells = 0.02;

struct Lattice {
    double t = 0.0, px = 0.0, py = 0.0;
};

// Whitened power spectrum, sampled anywhere by bilinear interpolation with the real transform's
// symmetry.
struct Spectrum {
    int rows = 0, cols = 0, half = 0;
    Plane s;  // rows x half, |X|^2 / ring mean

    double at(long k, long l) const {
        k %= rows;
        if (k < 0) k += rows;
        l %= cols;
        if (l < 0) l += cols;
        if (l >= half) {
            l = cols - l;
            k = (rows - k) % rows;
        }
        return s(k, l);
    }
    double sample(double fy, double fx) const {
        const double k = fy * rows, l = fx * cols;
        const double k0 = std::floor(k), l0 = std::floor(l), a = k - k0, b = l - l0;
        const long ik = static_cast<long>(k0), il = static_cast<long>(l0);
        return (1 - a) * ((1 - b) * at(ik, il) + b * at(ik, il + 1)) +
               a * ((1 - b) * at(ik + 1, il) + b * at(ik + 1, il + 1));
    }
};

struct Harmonic {
    double mx, my, w;  // m / n along the mask's axes, the peak's weight |P(m mod n)|^2
};

double hann(int i, int n) { return 0.5 - 0.5 * std::cos(kTwoPi * (i + 0.5) / n); }

Spectrum whitened_spectrum(const Plane& x, double& max_frequency, double pitch) {
    const int R = static_cast<int>(x.rows()), C = static_cast<int>(x.cols());
    Plane win(R, C);
    double sw = 0, swx = 0;
    for (int r = 0; r < R; ++r)
        for (int c = 0; c < C; ++c) {
            const double w = hann(r, R) * hann(c, C);
            win(r, c) = w;
            sw += w;
            swx += w * x(r, c);
        }
    // The window's weighted mean removed: no DC peak leaking into the lowest harmonics.
    const Plane y = win * (x - swx / sw);
    Fft2 fft(R, C);
    const ComplexPlane X = fft.forward(y);
    Spectrum sp;
    sp.rows = R;
    sp.cols = C;
    sp.half = fft.half_cols();
    sp.s = X.abs2();
    const int N = std::max(R, C);
    const int nb = N;  // rings of width 1 / N cycles per pixel out to the corner (sqrt 2 / 2)
    std::vector<double> sum(nb, 0.0), cnt(nb, 0.0);
    std::vector<double> noise;
    auto ring = [&](int k, int l, double& rho) {
        const double fy = (k <= R / 2 ? k : k - R) / double(R), fx = l / double(C);
        rho = std::hypot(fx, fy);
        return std::min(nb - 1, static_cast<int>(rho * N));
    };
    for (int k = 0; k < R; ++k)
        for (int l = 0; l < sp.half; ++l) {
            double rho;
            const int b = ring(k, l, rho);
            sum[b] += sp.s(k, l);
            cnt[b] += 1;
            if (rho >= kNoiseRing && rho <= 0.5) noise.push_back(sp.s(k, l));
        }
    std::vector<double> mean(nb, 0.0);
    for (int b = 0; b < nb; ++b) mean[b] = cnt[b] > 0 ? sum[b] / cnt[b] : 0.0;
    // Empty rings (never for rings inside the frame's band) take their inner neighbour's mean.
    for (int b = 1; b < nb; ++b)
        if (cnt[b] == 0) mean[b] = mean[b - 1];
    const double floor_level = noise.empty() ? 0.0 : median_of(noise);
    // The usable band: from the DC's neighbourhood out to the first ring at the noise floor.
    const int b_first = static_cast<int>(std::ceil(kDcBins));
    int b_max = b_first;
    while (b_max + 1 < nb && mean[b_max + 1] > kSignalOverNoise * floor_level) ++b_max;
    max_frequency = std::min(double(b_max) / N, kMaxCellHarmonic / pitch);
    for (int k = 0; k < R; ++k)
        for (int l = 0; l < sp.half; ++l) {
            double rho;
            const int b = ring(k, l, rho);
            sp.s(k, l) = mean[b] > 0 ? sp.s(k, l) / mean[b] : 0.0;
        }
    return sp;
}

// Weighted mean of the whitened spectrum at the comb of lattice L, harmonics with
// kDcBins / N <= |f| <= band.
double comb_score(const Spectrum& sp, const std::vector<Harmonic>& hs, const Lattice& L,
                  double band, double dc) {
    const double ct = std::cos(L.t), st = std::sin(L.t);
    double s = 0, w = 0;
    for (const Harmonic& h : hs) {
        const double ax = h.mx / L.px, ay = h.my / L.py;
        const double fx = ct * ax + st * ay, fy = -st * ax + ct * ay;
        const double rho = std::hypot(fx, fy);
        if (rho > band || rho < dc) continue;
        s += h.w * sp.sample(fy, fx);
        w += h.w;
    }
    return w > 0 ? s / w : 0.0;
}

// Best lattice on the grid centre + (i, j, k) step, |i| <= ni, |j|, |k| <= np.
Lattice grid_search(const Spectrum& sp, const std::vector<Harmonic>& hs, const Lattice& centre,
                    double step_t, double step_p, int ni, int np, double band, double dc,
                    const FftStartOptions& o, double nominal, double& best_score) {
    const double t_max = o.max_rotation_deg * std::numbers::pi / 180.0;
    const double p_lo = nominal * (1 - o.pitch_range), p_hi = nominal * (1 + o.pitch_range);
    Lattice best = centre;
    best_score = -1.0;
    for (int i = -ni; i <= ni; ++i)
        for (int j = -np; j <= np; ++j)
            for (int k = -np; k <= np; ++k) {
                Lattice L{std::clamp(centre.t + i * step_t, -t_max, t_max),
                          std::clamp(centre.px * (1 + j * step_p), p_lo, p_hi),
                          std::clamp(centre.py * (1 + k * step_p), p_lo, p_hi)};
                const double s = comb_score(sp, hs, L, band, dc);
                if (s > best_score) {
                    best_score = s;
                    best = L;
                }
            }
    return best;
}

// Parabolic vertex offset in (-0.5, 0.5) through three samples around a maximum.
double vertex(double a, double b, double c) {
    const double d = a - 2 * b + c;
    return d < 0 ? std::clamp(0.5 * (a - c) / d, -0.5, 0.5) : 0.0;
}

double bilinear(const Plane& x, double px, double py) {
    const int R = static_cast<int>(x.rows()), C = static_cast<int>(x.cols());
    const double fx = std::clamp(px, 0.0, C - 1.0), fy = std::clamp(py, 0.0, R - 1.0);
    const int c0 = std::min(static_cast<int>(fx), C - 2 < 0 ? 0 : C - 2);
    const int r0 = std::min(static_cast<int>(fy), R - 2 < 0 ? 0 : R - 2);
    const int c1 = std::min(c0 + 1, C - 1), r1 = std::min(r0 + 1, R - 1);
    const double a = fy - r0, b = fx - c0;
    return (1 - a) * ((1 - b) * x(r0, c0) + b * x(r0, c1)) +
           a * ((1 - b) * x(r1, c0) + b * x(r1, c1));
}

// The capture folded onto one period of lattice L: each used pixel's lattice coordinates modulo
// n, binned at q bins per cell, averaged (empty bins take the mean). Every stride-th row and
// column is used.
Plane fold(const Plane& x, const Lattice& L, int n, int q, int stride) {
    const int R = static_cast<int>(x.rows()), C = static_cast<int>(x.cols()), G = n * q;
    const double ct = std::cos(L.t), st = std::sin(L.t);
    Plane sum = Plane::Zero(G, G), cnt = Plane::Zero(G, G);
    // The bin of lattice coordinate a (in bins) modulo G, in floating point (the integer modulo
    // of every pixel cost more than the rest of the fold): floor(a) - G floor(floor(a) / G) is
    // exact for the bin counts of a frame.
    const double gd = G, sa = q / L.px, sb = q / L.py;
    auto wrap = [gd, G](double a) {
        const double f = std::floor(a);
        return std::min(G - 1, static_cast<int>(f - gd * std::floor(f / gd)));
    };
    for (int r = 0; r < R; r += stride)
        for (int c = 0; c < C; c += stride) {
            const double u = ct * c - st * r, v = st * c + ct * r;
            const int ia = wrap(u * sa), ib = wrap(v * sb);
            sum(ib, ia) += x(r, c);
            cnt(ib, ia) += 1;
        }
    const double filled_mean = sum.sum() / std::max(1.0, cnt.sum());
    Plane folded(G, G);
    for (int i = 0; i < G; ++i)
        for (int j = 0; j < G; ++j)
            folded(i, j) = cnt(i, j) > 0 ? sum(i, j) / cnt(i, j) : filled_mean;
    return folded;
}

// Cyclic cross-correlation of a fold with the pattern's open cells (their spectrum `cells`).
Plane fold_correlation(const Plane& folded, const ComplexPlane& cells) {
    const int G = static_cast<int>(folded.rows());
    Fft2 fft(G, G);
    return fft.inverse((fft.forward(folded) * cells.conjugate()).eval());
}

}  // namespace

FftStart fft_lattice_start(const Plane& frame, const Pattern& pattern, const FftStartOptions& o) {
    const int R = static_cast<int>(frame.rows()), C = static_cast<int>(frame.cols());
    if (R < 8 || C < 8) throw InvalidInput("calibrate: the capture is smaller than 8 x 8 pixels");
    if (pattern.pinholes.empty() || pattern.n < 1)
        throw InvalidInput("calibrate: the mask has no open cell");
    const int n = pattern.n;
    const double nominal = o.nominal_pitch_px;
    const double bg = median_of(std::vector<double>(frame.data(), frame.data() + frame.size()));
    const Plane x = frame - bg;

    // 1. Pitch and rotation.
    FftStart out;
    const Spectrum sp = whitened_spectrum(x, out.max_frequency, nominal);
    const int N = std::max(R, C);
    const double dc = kDcBins / N;
    std::vector<std::complex<double>> dft(static_cast<std::size_t>(n) * n, 0.0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            std::complex<double> s = 0;
            for (const Cell& c : pattern.pinholes)
                s += std::polar(1.0, -kTwoPi * double(a * c.col + b * c.row) / n);
            dft[static_cast<std::size_t>(b) * n + a] = s;
        }
    std::vector<Harmonic> hs;
    const int M =
        static_cast<int>(std::ceil(out.max_frequency * n * nominal * (1 + o.pitch_range)));
    for (int my = 0; my <= M; ++my)
        for (int mx = -M; mx <= M; ++mx) {
            if (my == 0 && mx <= 0) continue;  // the other half is the same by symmetry
            const double w = std::norm(
                dft[static_cast<std::size_t>(((my % n) + n) % n) * n + ((mx % n) + n) % n]);
            if (w <= 0) continue;
            const double bound = std::hypot(double(mx), double(my)) / n;
            if (bound / (nominal * (1 + o.pitch_range)) > out.max_frequency) continue;
            hs.push_back({double(mx) / n, double(my) / n, w});
        }
    double band =
        std::min(out.max_frequency, std::max(kFirstHarmonics / (n * nominal), kFirstBins / N));
    double step = kStepBins / (band * N);
    const double t_max = o.max_rotation_deg * std::numbers::pi / 180.0;
    const int ni = static_cast<int>(std::ceil(t_max / step));
    const int np = static_cast<int>(std::ceil(o.pitch_range / step));
    Lattice best = grid_search(sp, hs, {0.0, nominal, nominal}, step, step, ni, np, band, dc, o,
                               nominal, out.score);
    while (band < out.max_frequency) {
        band = std::min(out.max_frequency, 2 * band);
        step = kStepBins / (band * N);
        best = grid_search(sp, hs, best, step, step, 2, 2, band, dc, o, nominal, out.score);
    }
    best = grid_search(sp, hs, best, 0.5 * step, 0.5 * step, 1, 1, band, dc, o, nominal, out.score);

    // 2. The lattice refined by the fold's sharpness (the correlation peak of the fold with the
    // open cells: a wrong pitch or rotation smears the periods over each other), a 3 x 3 x 3 grid
    // around the best point with the step halved each time, on at most kFoldPixels pixels.
    const int q = std::clamp(static_cast<int>(std::floor(nominal)), 2, kMaxBinsPerCell);
    const int G = n * q;
    Plane deltas = Plane::Zero(G, G);
    for (const Cell& c : pattern.pinholes) deltas(c.row * q % G, c.col * q % G) = 1.0;
    Fft2 small(G, G);
    const ComplexPlane cells = small.forward(deltas);
    const int stride =
        std::max(1, static_cast<int>(std::floor(std::sqrt(double(R) * C / kFoldPixels))));
    auto sharpness = [&](const Lattice& L) {
        return fold_correlation(fold(x, L, n, q, stride), cells).maxCoeff();
    };
    double best_sharp = sharpness(best);
    for (double st_step = step; st_step > kFinestStepCells / (N / nominal); st_step *= 0.5) {
        const Lattice centre = best;
        for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j)
                for (int k = -1; k <= 1; ++k) {
                    if (i == 0 && j == 0 && k == 0) continue;
                    const Lattice L{std::clamp(centre.t + i * st_step, -t_max, t_max),
                                    centre.px * (1 + j * st_step), centre.py * (1 + k * st_step)};
                    const double v = sharpness(L);
                    if (v > best_sharp) {
                        best_sharp = v;
                        best = L;
                    }
                }
    }
    const double ct = std::cos(best.t), st = std::sin(best.t);

    // 3. Position modulo one period: the fold at the lattice found, every pixel.
    const Plane corr = fold_correlation(fold(x, best, n, q, 1), cells);
    auto wrap = [G](long v) { return static_cast<int>(((v % G) + G) % G); };
    Eigen::Index pb = 0, pa = 0;
    corr.maxCoeff(&pb, &pa);
    auto cyc = [&](long i, long j) { return corr(wrap(i), wrap(j)); };
    const double da = vertex(cyc(pb, pa - 1), cyc(pb, pa), cyc(pb, pa + 1));
    const double db = vertex(cyc(pb - 1, pa), cyc(pb, pa), cyc(pb + 1, pa));
    const double a0 = (double(pa) + da + 0.5) / q, b0 = (double(pb) + db + 0.5) / q;

    // 4. Which period.
    const int ncol = n * pattern.tiles_cols, nrow = n * pattern.tiles_rows;
    double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
    for (const auto& [cx, cy] :
         {std::pair{0.0, 0.0}, {C - 1.0, 0.0}, {0.0, R - 1.0}, {C - 1.0, R - 1.0}}) {
        const double u = (ct * cx - st * cy) / best.px, v = (st * cx + ct * cy) / best.py;
        a_lo = std::min(a_lo, u);
        a_hi = std::max(a_hi, u);
        b_lo = std::min(b_lo, v);
        b_hi = std::max(b_hi, v);
    }
    struct Placement {
        double a, b;
        std::vector<double> values;
    };
    std::vector<Placement> places;
    const int i_lo = static_cast<int>(std::floor((a_lo - a0 - ncol) / n)) - 1;
    const int i_hi = static_cast<int>(std::ceil((a_hi - a0) / n)) + 1;
    const int j_lo = static_cast<int>(std::floor((b_lo - b0 - nrow) / n)) - 1;
    const int j_hi = static_cast<int>(std::ceil((b_hi - b0) / n)) + 1;
    std::size_t most = 0;
    for (int j = j_lo; j <= j_hi; ++j)
        for (int i = i_lo; i <= i_hi; ++i) {
            Placement p{a0 + n * i, b0 + n * j, {}};
            for (int tr = 0; tr < pattern.tiles_rows; ++tr)
                for (int tc = 0; tc < pattern.tiles_cols; ++tc)
                    for (const Cell& cell : pattern.pinholes) {
                        const double u = (p.a + cell.col + tc * n) * best.px;
                        const double v = (p.b + cell.row + tr * n) * best.py;
                        const double sx = ct * u + st * v, sy = -st * u + ct * v;
                        if (sx < 0 || sy < 0 || sx > C - 1 || sy > R - 1) continue;
                        p.values.push_back(bilinear(x, sx, sy));
                    }
            if (p.values.empty()) continue;
            most = std::max(most, p.values.size());
            places.push_back(std::move(p));
        }
    double tau = 0.0;
    for (const Placement& p : places)
        if (p.values.size() == most) {
            tau = std::max(0.0, 0.5 * median_of(p.values));
            break;
        }
    const double fc = 0.5 * (C - 1), fr = 0.5 * (R - 1);
    double best_score = -1e300, best_dist = 1e300, scale = 0.0;
    const Placement* chosen = nullptr;
    for (const Placement& p : places)
        for (double v : p.values) scale = std::max(scale, std::abs(v - tau));
    for (const Placement& p : places) {
        double s = 0;
        for (double v : p.values) s += v - tau;
        // Mask centre's distance from the frame centre.
        const double u = (p.a + 0.5 * (ncol - 1)) * best.px, v = (p.b + 0.5 * (nrow - 1)) * best.py;
        const double d = std::hypot(ct * u + st * v - fc, -st * u + ct * v - fr);
        const double tol = 1e-9 * scale * std::max<std::size_t>(most, 1);
        if (s > best_score + tol || (s >= best_score - tol && d < best_dist)) {
            best_score = std::max(s, best_score);
            best_dist = d;
            chosen = &p;
        }
    }
    if (chosen == nullptr)
        throw InvalidInput("calibrate: no placement of the mask puts a spot in the frame");
    const double u = chosen->a * best.px, v = chosen->b * best.py;
    out.lattice.x0 = ct * u + st * v;
    out.lattice.y0 = -st * u + ct * v;
    out.lattice.rotation_rad = best.t;
    out.lattice.pitch_x_px = best.px;
    out.lattice.pitch_y_px = best.py;
    return out;
}

}  // namespace pinmask::calibrate
