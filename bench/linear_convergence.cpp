#include "bench/linear_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "bench/error_time_run.hpp"
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/image/image_io.hpp"
#include "decode/capture/preprocess.hpp"
#include "decode/solvers/convolution.hpp"
#include "design/psf/psf_exact.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/scenes.hpp"

namespace pinmask {
namespace {

int next_pow2(int n) {
    int m = 1;
    while (m < n) m *= 2;
    return m;
}

// The capture window of the linear model, rendered without decode/'s operator: a full linear
// convolution of the working-grid scene with the PSF on a power-of-two grid (no wrap-around),
// read at the window the operator's geometry defines (the PSF's element (floor(pr/2),
// floor(pc/2)) is its origin).
Plane render_window(const Plane& psf, const Plane& scene, const ConvGeometry& g) {
    const int pr = int(psf.rows()), pc = int(psf.cols());
    const int R = next_pow2(g.work_rows + pr - 1), C = next_pow2(g.work_cols + pc - 1);
    const Fft2 fft(R, C);
    Plane a = Plane::Zero(R, C), b = Plane::Zero(R, C);
    a.block(0, 0, pr, pc) = psf;
    b.block(0, 0, g.work_rows, g.work_cols) = scene;
    const Plane full = fft.inverse(ComplexPlane(fft.forward(a) * fft.forward(b)));
    return full.block(g.crop_row + pr / 2, g.crop_col + pc / 2, g.capture_rows, g.capture_cols);
}

// The bounding box of the values above `floor` (the PSF's support).
Plane cut_to_support(const Plane& p, double floor) {
    int r0 = int(p.rows()), r1 = -1, c0 = int(p.cols()), c1 = -1;
    for (int r = 0; r < p.rows(); ++r)
        for (int c = 0; c < p.cols(); ++c)
            if (p(r, c) > floor) {
                r0 = std::min(r0, r);
                r1 = std::max(r1, r);
                c0 = std::min(c0, c);
                c1 = std::max(c1, c);
            }
    if (r1 < 0) throw invalid_field("psf", "all zero", "needs light");
    return p.block(r0, c0, r1 - r0 + 1, c1 - c0 + 1);
}

Plane natural_scene(int rows, int cols, std::uint64_t seed) {
    SceneSpec s;
    s.kind = SceneKind::kNatural;
    s.seed = seed;
    Plane x = make_scene(s, rows, cols).channels.at(0);
    return x;
}

}  // namespace

LinearProblem make_linear_problem(const std::string& name, const Plane& psf, int capture_rows,
                                  int capture_cols, const Plane& scene, double snr_db,
                                  double lambda_relative, std::uint64_t seed) {
    LinearProblem P;
    P.name = name;
    P.psf = psf / psf.sum();
    P.geometry = make_conv_geometry(ConvModel::kLinear, capture_rows, capture_cols, int(psf.rows()),
                                    int(psf.cols()));
    if (scene.rows() != P.geometry.work_rows || scene.cols() != P.geometry.work_cols) {
        throw invalid_field("scene",
                            std::to_string(scene.rows()) + " x " + std::to_string(scene.cols()),
                            "must be the working grid " + std::to_string(P.geometry.work_rows) +
                                " x " + std::to_string(P.geometry.work_cols));
    }
    P.scene = scene;
    P.capture = render_window(P.psf, P.scene, P.geometry);
    const double sigma = std::sqrt(P.capture.square().mean()) * std::pow(10.0, -snr_db / 20.0);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    for (Eigen::Index i = 0; i < P.capture.size(); ++i) P.capture.data()[i] += noise(rng);
    P.lambda = lambda_relative * P.capture.abs().maxCoeff();
    return P;
}

std::vector<LinearProblem> linear_convergence_cases(double scale,
                                                    const std::string& diffusercam_psf_path) {
    if (!(scale > 0.0 && scale <= 1.0))
        throw invalid_field("scale", std::to_string(scale), "must be in (0, 1]");
    // Downsampling rounds for the scale (1, 0.5, 0.25, ...), by 2 x 2 box averaging.
    const int rounds = int(std::lround(-std::log2(scale)));
    std::vector<LinearProblem> out;
    const Mask mask = error_time_paper_mask();
    const int sensor_r = mask.camera.sensor_rows >> rounds;
    const int sensor_c = mask.camera.sensor_cols >> rounds;
    std::uint64_t seed = 11;
    for (double u : {mask.camera.object_distance_m, 2.0}) {
        ExactPsfOptions e;
        e.object_distance_m = u;
        // The kernel cut to one period, as the cyclic model's: the problems the held iteration
        // counts were measured on (the exact PSF's own kernel reaches across the frame with
        // this camera's diffraction tails, a larger padded grid and another problem).
        e.kernel.max_width_px = mask.pattern.n * mask.psf.pixels_per_cell;
        const Plane full = exact_psf(mask, e);
        const Plane psf = box_downsample(cut_to_support(full, 1e-12 * full.maxCoeff()), rounds);
        const ConvGeometry g = make_conv_geometry(ConvModel::kLinear, sensor_r, sensor_c,
                                                  int(psf.rows()), int(psf.cols()));
        out.push_back(make_linear_problem(
            u == mask.camera.object_distance_m ? "paper-full-sensor" : "refocused-2m", psf,
            sensor_r, sensor_c, natural_scene(g.work_rows, g.work_cols, seed), 30.0, 3e-3,
            seed + 1));
        seed += 2;
    }
    if (!diffusercam_psf_path.empty()) {
        Plane psf = read_image(diffusercam_psf_path).image.channels.at(0);
        psf = (psf - corner_background(psf)).max(0.0);
        psf = box_downsample(psf, 2 + rounds);  // the tutorial's 4x, then the scale
        const int cr = int(psf.rows()), cc = int(psf.cols());
        const ConvGeometry g = make_conv_geometry(ConvModel::kLinear, cr, cc, cr, cc);
        out.push_back(make_linear_problem("diffusercam", psf, cr, cc,
                                          natural_scene(g.work_rows, g.work_cols, seed), 30.0, 1e-3,
                                          seed + 1));
    }
    return out;
}

IterationsToQuality tv_l2_iterations_to_quality(const LinearProblem& P, TvL2Options o,
                                                double within_db, int max_iterations,
                                                int reference_iterations) {
    const ConvGeometry& g = P.geometry;
    const ConvolutionOperator op(P.psf, g);
    const Plane truth = crop_to_capture(g, P.scene);
    o.lambda = P.lambda;
    o.tolerance = 0.0;
    o.record_history = false;
    o.max_iterations = reference_iterations;
    IterationsToQuality out;
    out.converged_psnr_db = psnr_db(crop_to_capture(g, solve_tv_l2(op, P.capture, o).image), truth);
    o.max_iterations = max_iterations;
    out.psnr_db.assign(std::size_t(max_iterations), 0.0);
    o.observe = [&](int k, const Plane& x) {
        out.psnr_db[std::size_t(k - 1)] = psnr_db(crop_to_capture(g, x), truth);
    };
    solve_tv_l2(op, P.capture, o);
    int last_outside = 0;
    for (int k = 1; k <= max_iterations; ++k)
        if (std::abs(out.psnr_db[std::size_t(k - 1)] - out.converged_psnr_db) > within_db)
            last_outside = k;
    out.iterations = last_outside + 1;
    out.reached = last_outside < max_iterations;
    out.psnr_at_iterations_db =
        out.reached ? out.psnr_db[std::size_t(out.iterations - 1)] : out.psnr_db.back();
    return out;
}

}  // namespace pinmask
