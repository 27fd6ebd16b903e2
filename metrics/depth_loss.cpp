#include "metrics/depth_loss.hpp"

#include <cmath>
#include <random>
#include <string>

#include "core/error.hpp"
#include "core/field_names.hpp"
#include "core/fft.hpp"
#include "core/units.hpp"
#include "decode/decoder.hpp"
#include "design/psf.hpp"
#include "design/psf_exact.hpp"
#include "design/working_distance.hpp"
#include "simulate/image_quality.hpp"
#include "simulate/noise_model.hpp"
#include "simulate/scenes.hpp"
#include "simulate/simulate.hpp"

namespace pinmask {
namespace {

// The scene cyclically shifted to best match x (maximum of the circular cross-correlation).
Plane registered_scene(const Plane& x, const Plane& scene) {
    const int r = static_cast<int>(x.rows()), c = static_cast<int>(x.cols());
    const Fft2 fft(r, c);
    const Plane corr = fft.inverse(fft.forward(x) * fft.forward(scene).conjugate());
    Eigen::Index br = 0, bc = 0;
    corr.maxCoeff(&br, &bc);  // x(i) ~ scene(i - shift)
    Plane out(r, c);
    for (int i = 0; i < r; ++i) {
        for (int j = 0; j < c; ++j) {
            out(i, j) = scene(((i - br) % r + r) % r, ((j - bc) % c + c) % c);
        }
    }
    return out;
}

Plane noisy(const Plane& clean, double snr_db, std::uint64_t seed) {
    if (std::isinf(snr_db)) return clean;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n(0.0, sigma_for_snr(clean.square().mean(), snr_db));
    Plane out = clean;
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] += n(rng);
    return out;
}

double decoded_psnr(const Plane& capture, const Plane& psf, const Plane& scene, bool tv,
                    const DepthOptions& o) {
    DecodeOptions d;
    d.method = tv ? DecodeMethod::kTv : DecodeMethod::kWiener;
    d.wiener.nsr = o.wiener_nsr;
    d.tv.lambda = o.tv_lambda;
    d.iterative.max_iterations = o.tv_iterations;
    d.iterative.record_history = false;
    const Plane x = decode_plane(capture, psf, d).image;
    return psnr_db(x, registered_scene(x, scene));
}

}  // namespace

void DepthOptions::validate() const {
    if (scenes.empty()) throw invalid_field("scenes", "none", "need at least one scene");
    if (std::isnan(snr_db) || snr_db == -std::numeric_limits<double>::infinity()) {
        throw invalid_field("snr_db", std::to_string(snr_db), "must be a number or inf");
    }
    if (!(wiener_nsr > 0.0) || !std::isfinite(wiener_nsr)) {
        throw invalid_field("wiener_nsr", std::to_string(wiener_nsr), "must be finite and > 0");
    }
    if (!(tv_lambda > 0.0) || !std::isfinite(tv_lambda)) {
        throw invalid_field("tv_lambda", std::to_string(tv_lambda), "must be finite and > 0");
    }
    if (tv_iterations < 1) {
        throw invalid_field("tv_iterations", std::to_string(tv_iterations), "must be >= 1");
    }
}

std::vector<double> depth_range(double from_m, double to_m, int steps) {
    if (!(from_m > 0.0) || !std::isfinite(from_m)) {
        throw invalid_field(field_ref("from_m"), format_length(from_m), "must be finite and > 0");
    }
    if (!(to_m > from_m)) {
        throw invalid_field(field_ref("to_m"), format_length(to_m),
                            "must be greater than " + field_ref("from_m") + " (inf allowed)");
    }
    if (steps < 2 || steps > 1000) {
        throw invalid_field(field_ref("steps"), std::to_string(steps), "must be between 2 and 1000");
    }
    const double x0 = 1.0 / from_m, x1 = std::isinf(to_m) ? 0.0 : 1.0 / to_m;
    std::vector<double> out;
    for (int i = 0; i < steps; ++i) {
        const double x = x0 + (x1 - x0) * i / (steps - 1);
        out.push_back(i == steps - 1 ? to_m : 1.0 / x);
    }
    return out;
}

std::vector<DepthRecord> depth_analysis(const Mask& mask, const std::vector<double>& distances,
                                        const DepthOptions& o) {
    o.validate();
    if (distances.empty()) throw invalid_field("distances", "none", "need at least one distance");
    for (double u : distances) check_object_distance(mask.camera, u, "object distance");
    const Plane psf = mask_psf(mask);
    const int m = static_cast<int>(psf.rows());
    const int n = mask.pattern.n, ppc = mask.psf.pixels_per_cell;
    std::vector<Plane> scenes;
    for (const std::string& name : o.scenes) {
        scenes.push_back(make_scene(scene_from_name(name), m, m).channels[0]);
    }
    std::vector<DepthRecord> out;
    for (double u : distances) {
        DepthRecord r;
        r.object_distance_m = u;
        r.pixels_per_cell = pixels_per_cell_at(mask.camera, u);
        r.period_px = n * r.pixels_per_cell;
        r.lsi_mismatch_px = n * std::fabs(r.pixels_per_cell - ppc);
        // A window holding the whole tiled mask's spots plus the scene's extent on each side.
        const int tiles = std::max(mask.pattern.tiles_rows, mask.pattern.tiles_cols);
        ExactPsfOptions eo;
        eo.object_distance_m = u;
        // Even, so the axis (at W/2) falls on a pixel corner as in the integer model's period.
        const int w = static_cast<int>(
            std::min(65536.0, std::ceil(tiles * r.period_px + 2.0 * ppc) + 2.0 * m));
        eo.rows = eo.cols = w + (w % 2);
        const Plane exact = exact_psf(mask, eo);
        const TileOrigin at = centred_tile_origin(eo.rows, eo.cols, m, m);
        double wiener = 0, tv = 0;
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const std::uint64_t seed = o.seed * 1000003ULL + s;
            const Plane ref = noisy(cyclic_capture(scenes[s], psf), o.snr_db, seed);
            const Plane cap =
                noisy(Plane(linear_capture(scenes[s], exact).block(at.row, at.col, m, m)), o.snr_db,
                      seed);
            wiener += decoded_psnr(ref, psf, scenes[s], false, o) -
                      decoded_psnr(cap, psf, scenes[s], false, o);
            if (o.with_tv) {
                tv += decoded_psnr(ref, psf, scenes[s], true, o) -
                      decoded_psnr(cap, psf, scenes[s], true, o);
            }
        }
        r.wiener_psnr_loss_db = wiener / scenes.size();
        if (o.with_tv) r.tv_psnr_loss_db = tv / scenes.size();
        out.push_back(r);
    }
    return out;
}

}  // namespace pinmask
