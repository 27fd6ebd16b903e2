#include "optimize/simulate/simulate.hpp"

#include <limits>
#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"
#include "decode/solvers/precision.hpp"
#include "decode/solvers/psf2otf.hpp"

namespace pinmask {
namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) {
    return std::to_string(r) + " x " + std::to_string(c);
}

// Floor division and modulo for possibly negative numerators.
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int pos_mod(int a, int b) { return ((a % b) + b) % b; }

std::mt19937_64 stream_rng(std::uint64_t seed, std::uint32_t stream, int channel) {
    std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                      stream, static_cast<std::uint32_t>(channel)};
    return std::mt19937_64(seq);
}

// The float32 convolutions: inputs scaled to magnitude <= 1 (a by max|a|, the transfer function
// by sum|b| >= max|F[b]|), transformed with FFTW float, scaled back in double.
double scale_of(double v) { return v > 0.0 ? v : 1.0; }

// a (*) b for b given by its transfer function (half spectrum, double).
Plane convolve_single(const Plane& a, const ComplexPlane& b_spectrum, double b_l1) {
    const double sa = scale_of(a.abs().maxCoeff()), sb = scale_of(b_l1);
    const Fft2f fft(static_cast<int>(a.rows()), static_cast<int>(a.cols()));
    ComplexPlaneF spec, scratch;
    fft.forward((a / sa).cast<float>(), spec);
    spec *= (b_spectrum / sb).cast<std::complex<float>>();
    PlaneF out;
    fft.inverse(spec, out, scratch);
    return out.cast<double>() * (sa * sb);
}

// a (*) b, circular on a's grid, both real planes of the same size.
Plane convolve_single(const Plane& a, const Plane& b) {
    const double sa = scale_of(a.abs().maxCoeff()), sb = scale_of(b.abs().sum());
    const Fft2f fft(static_cast<int>(a.rows()), static_cast<int>(a.cols()));
    ComplexPlaneF spec, spec_b, scratch;
    fft.forward((a / sa).cast<float>(), spec);
    fft.forward((b / sb).cast<float>(), spec_b);
    spec *= spec_b;
    PlaneF out;
    fft.inverse(spec, out, scratch);
    return out.cast<double>() * (sa * sb);
}

constexpr std::uint32_t kCaptureStream = 0;
constexpr std::uint32_t kDarkStream = 1;

}  // namespace

void SimulationOptions::validate() const {
    pinmask::validate(noise);
    if (full_sensor && (sensor_rows < 1 || sensor_cols < 1)) {
        throw invalid_field("sensor size",
                            std::to_string(sensor_cols) + "x" + std::to_string(sensor_rows),
                            "must be at least 1 x 1 pixels");
    }
    if (dark_frame && noise.kind != NoiseKind::kPhoton) {
        throw invalid_field("dark_frame", "true",
                            "needs the photon noise model: the Gaussian SNR model and the "
                            "noiseless capture have no leak, dark current or read noise to record");
    }
}

Plane cyclic_capture(const Plane& scene, const Plane& psf, bool single_precision) {
    if (psf.size() == 0 || !psf.isFinite().all() || !(psf.sum() > 0.0)) {
        throw InvalidInput("simulate: the PSF must be non-empty and finite, with sum > 0");
    }
    if (scene.rows() != psf.rows() || scene.cols() != psf.cols()) {
        throw InvalidInput("simulate: the scene is " + size_text(scene.rows(), scene.cols()) +
                           ", the period (the PSF) is " + size_text(psf.rows(), psf.cols()) +
                           ": they must be equal");
    }
    if (!scene.isFinite().all()) throw InvalidInput("simulate: the scene has non-finite values");
    const int rows = static_cast<int>(psf.rows()), cols = static_cast<int>(psf.cols());
    Plane c;
    if (single_precision) {  // |H| <= sum|a|: the transfer function scaled to at most 1
        c = convolve_single(scene, psf2otf(psf, rows, cols), psf.abs().sum());
    } else {
        const Fft2 fft(rows, cols);
        c = fft.inverse(fft.forward(scene) * psf2otf(psf, rows, cols));
    }
    if (scene.minCoeff() >= 0.0 && psf.minCoeff() >= 0.0) c = c.max(0.0);
    return c;
}

Plane linear_capture(const Plane& scene, const Plane& w, bool single_precision) {
    if (scene.size() == 0 || w.size() == 0) throw InvalidInput("linear_capture: empty input");
    if (!is_all_finite(scene) || !is_all_finite(w)) {
        throw InvalidInput("linear_capture: the scene or the PSF holds NaN or Inf");
    }
    const int mr = static_cast<int>(scene.rows()), mc = static_cast<int>(scene.cols());
    const int R = static_cast<int>(w.rows()), C = static_cast<int>(w.cols());
    const int fr = R + mr - 1, fc = C + mc - 1;  // the full linear convolution, no wrap
    check_memory(8.0 * fr * fc * 4.0, "the linear convolution of the exact-geometry capture");
    Plane a = Plane::Zero(fr, fc), b = Plane::Zero(fr, fc);
    a.topLeftCorner(mr, mc) = scene;
    b.topLeftCorner(R, C) = w;
    Plane full;
    if (single_precision) {
        full = convolve_single(a, b);
    } else {
        const Fft2 fft(fr, fc);
        full = fft.inverse(fft.forward(a) * fft.forward(b));
    }
    // full(k) = sum_i x(i) w(k - i); c(r) = full(r + floor(m / 2)).
    Plane c = full.block(mr / 2, mc / 2, R, C);
    if (scene.minCoeff() >= 0.0 && w.minCoeff() >= 0.0) c = c.max(0.0);
    return c;
}

bool simulate_in_single(Precision precision, long long rows, long long cols) {
    return precision == Precision::kSingle ||
           (precision == Precision::kAuto && rows * cols >= kSinglePrecisionMinPixels);
}

TileOrigin centred_tile_origin(int frame_rows, int frame_cols, int period_rows, int period_cols) {
    return {floor_div(frame_rows - period_rows, 2), floor_div(frame_cols - period_cols, 2)};
}

Plane tile_period(const Plane& period, int rows, int cols, TileOrigin origin) {
    if (rows < 1 || cols < 1) {
        throw invalid_field("frame size", size_text(rows, cols), "must be at least 1 x 1");
    }
    if (period.size() == 0) throw InvalidInput("tile_period: the period is empty");
    check_memory(8.0 * rows * cols, "the " + size_text(rows, cols) + " sensor frame");
    const int pr = static_cast<int>(period.rows()), pc = static_cast<int>(period.cols());
    Plane out(rows, cols);
    for (int r = 0; r < rows; ++r) {
        const int sr = pos_mod(r - origin.row, pr);
        for (int c = 0; c < cols; ++c) out(r, c) = period(sr, pos_mod(c - origin.col, pc));
    }
    return out;
}

SimulatedCapture simulate_capture(const Image& scene, const Plane& psf, int open_cells,
                                  int total_cells, const SimulationOptions& options) {
    options.validate();
    if (scene.empty()) throw InvalidInput("simulate: the scene is empty");
    const int pr = static_cast<int>(psf.rows()), pc = static_cast<int>(psf.cols());
    SimulatedCapture out;
    int rows = pr, cols = pc;
    if (options.exact_psf) {
        rows = static_cast<int>(options.exact_psf->rows());
        cols = static_cast<int>(options.exact_psf->cols());
        out.origin = centred_tile_origin(rows, cols, pr, pc);
        out.whole_period_on_sensor = rows >= pr && cols >= pc;
    } else if (options.full_sensor) {
        rows = options.sensor_rows;
        cols = options.sensor_cols;
        out.origin = centred_tile_origin(rows, cols, pr, pc);
        out.whole_period_on_sensor = rows >= pr && cols >= pc;
    }
    // Frames held at once: clean, capture and dark per channel, plus one working plane.
    check_memory(8.0 * rows * cols * (3.0 * scene.n_channels() + 1.0), "the simulated frames");
    const NoiseModel& m = options.noise;
    const double scale = m.photons_per_pinhole * open_cells;  // electrons per normalised unit
    for (int ch = 0; ch < scene.n_channels(); ++ch) {
        Plane clean = options.exact_psf
                          ? linear_capture(scene.channels[ch], *options.exact_psf,
                                           simulate_in_single(options.precision, rows + pr - 1LL,
                                                              cols + pc - 1LL))
                          : cyclic_capture(scene.channels[ch], psf,
                                           simulate_in_single(options.precision, pr, pc));
        if (options.full_sensor && !options.exact_psf) {
            clean = tile_period(clean, rows, cols, out.origin);
        }
        std::mt19937_64 rng = stream_rng(options.seed, kCaptureStream, ch);
        Plane noisy = add_noise(clean, m, open_cells, total_cells, rng);
        double background = 0.0;
        double offset_e = 0.0;
        if (m.kind == NoiseKind::kPhoton) {
            const CaptureStats stats{clean.mean(), clean.square().mean(), open_cells, total_cells};
            offset_e = dark_offset_e(m, stats);
            background = offset_e / scale;
            noisy += background;
        }
        if (options.dark_frame) {
            // All-opaque film: the leak and the dark current as one Poisson mean, no signal.
            NoiseModel dark_model = m;
            dark_model.film_optical_density = std::numeric_limits<double>::infinity();
            dark_model.dark_current_e = offset_e;
            std::mt19937_64 dark_rng = stream_rng(options.seed, kDarkStream, ch);
            Plane dark =
                add_noise(Plane::Zero(rows, cols), dark_model, open_cells, total_cells, dark_rng);
            dark += offset_e / scale;
            out.dark.channels.push_back(std::move(dark));
        }
        out.capture.channels.push_back(std::move(noisy));
        out.clean.channels.push_back(std::move(clean));
        out.background.push_back(background);
    }
    return out;
}

}  // namespace pinmask
