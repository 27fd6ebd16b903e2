#include "optimize/metrics/depth_loss.hpp"

#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <random>
#include <string>
#include <thread>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/fft/fft.hpp"
#include "core/units/units.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/precision.hpp"
#include "design/optics/distance_list.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"

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

Plane noisy(const Plane& clean, const NoiseModel& noise, const Mask& mask, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const int n = mask.pattern.n;
    return add_noise(clean, noise, static_cast<int>(mask.pattern.pinholes.size()), n * n, rng);
}

// The centred m x m crop (origin floor(m / 2), as centred_tile_origin) of the linear capture
// linear_capture(scene, w) of the m x m scene through the 2m x 2m window w centred on the axis.
// full(k) = sum_i x(i) w(k - i) has k in [0, 3m - 2]; the crop is full(k) for k in
// [2 floor(m/2), 2 floor(m/2) + m), which a cyclic convolution of side 2m gives unwrapped
// (k + 2m > 3m - 2 and k - 2m < 0).
Plane capture_crop(const Plane& scene, const Plane& w) {
    const int m = static_cast<int>(scene.rows()), side = static_cast<int>(w.rows());
    Plane a = Plane::Zero(side, side);
    a.topLeftCorner(m, m) = scene;
    const Fft2 fft(side, side);
    const Plane full = fft.inverse(fft.forward(a) * fft.forward(w));
    const int k0 = 2 * (m / 2);
    Plane c = full.block(k0, k0, m, m);
    if (scene.minCoeff() >= 0.0 && w.minCoeff() >= 0.0) c = c.max(0.0);
    return c;
}

double decoded_psnr(const Plane& capture, const Plane& psf, const Plane& scene, bool tv, double nsr,
                    const DepthOptions& o) {
    DecodeOptions d;
    d.method = tv ? DecodeMethod::kTv : DecodeMethod::kWiener;
    d.wiener.nsr = nsr;
    d.tv.lambda = o.tv_lambda;
    d.iterative.max_iterations = o.tv_iterations;
    d.iterative.record_history = false;
    // As decode --precision auto: TV in float32 from 256 x 256 (decode/solvers/precision.hpp).
    d.single_precision = tv && capture.size() >= kSinglePrecisionMinPixels;
    const Plane x = decode_plane(capture, psf, d).image;
    return psnr_db(x, registered_scene(x, scene));
}

// Runs fn(0), ..., fn(count - 1) on up to `threads` threads (each index once; the results must
// not depend on the order). The first exception is rethrown after every thread has stopped.
void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& fn) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto work = [&] {
        for (std::size_t i = next++; i < count; i = next++) {
            try {
                fn(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
                next = count;  // no new work
            }
        }
    };
    const std::size_t extra = std::min<std::size_t>(count, std::max(threads, 1)) - 1;
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < extra; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace

void DepthOptions::validate() const {
    if (scenes.empty()) throw invalid_field(field_ref("scenes"), "none", "need at least one scene");
    pinmask::validate(noise);
    if (!wiener_nsr.tuned && (!(wiener_nsr.value > 0.0) || !std::isfinite(wiener_nsr.value))) {
        throw invalid_field(field_ref("wiener_nsr"), std::to_string(wiener_nsr.value),
                            "must be finite and > 0 (or tuned)");
    }
    if (!(tv_lambda > 0.0) || !std::isfinite(tv_lambda)) {
        throw invalid_field("tv_lambda", std::to_string(tv_lambda), "must be finite and > 0");
    }
    if (threads < 1 || threads > 256) {
        throw invalid_field("threads", std::to_string(threads), "must be between 1 and 256");
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
        throw invalid_field(field_ref("steps"), std::to_string(steps),
                            "must be between 2 and 1000");
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
    check_distinct_distances(distances, field_ref("distances"));
    const Plane psf = mask_psf(mask);
    const int m = static_cast<int>(psf.rows());
    const int n = mask.pattern.n, ppc = mask.psf.pixels_per_cell;
    std::vector<NamedScene> scenes;
    for (const std::string& name : o.scenes) {
        scenes.push_back({name, make_scene(scene_from_name(name), m, m)});
        scenes.back().image.channels.resize(1);  // grey: the first channel
    }
    double nsr = o.wiener_nsr.value;
    if (o.wiener_nsr.tuned) {
        SimulatedMetricsOptions sim;
        sim.seed = o.seed;
        sim.wiener_nsr = o.wiener_nsr;
        nsr =
            simulated_quality(psf, scenes, o.noise, static_cast<int>(mask.pattern.pinholes.size()),
                              n * n, SimulatedDecoder::kWiener, sim)
                .weight;
    }
    // The reference decodes: the cyclic capture does not depend on u.
    const std::size_t ns = scenes.size(), nd = distances.size();
    std::vector<double> ref_wiener(ns), ref_tv(ns);
    auto seed_of = [&](std::size_t s) { return o.seed * 1000003ULL + s; };
    parallel_for(ns, o.threads, [&](std::size_t s) {
        const Plane& x = scenes[s].image.channels[0];
        const Plane ref = noisy(cyclic_capture(x, psf), o.noise, mask, seed_of(s));
        ref_wiener[s] = decoded_psnr(ref, psf, x, false, nsr, o);
        if (o.with_tv) ref_tv[s] = decoded_psnr(ref, psf, x, true, nsr, o);
    });
    if (o.progress) o.progress(0, nd);
    // One task per (distance, scene); each writes its own slot, so the figures do not depend on
    // the thread count or the order.
    std::vector<double> wiener(nd * ns), tv(nd * ns);
    std::vector<std::size_t> scenes_done(nd, 0);
    std::size_t distances_done = 0;
    std::mutex progress_mutex;
    parallel_for(nd * ns, o.threads, [&](std::size_t task) {
        const std::size_t k = task / ns, s = task % ns;
        // The exact PSF within m pixels of the axis (at the window's centre, a pixel corner):
        // all the centred crop of the capture sees (capture_crop).
        ExactPsfOptions eo;
        eo.object_distance_m = distances[k];
        eo.rows = eo.cols = 2 * m;
        const Plane& x = scenes[s].image.channels[0];
        const Plane cap = noisy(capture_crop(x, exact_psf(mask, eo)), o.noise, mask, seed_of(s));
        wiener[task] = ref_wiener[s] - decoded_psnr(cap, psf, x, false, nsr, o);
        if (o.with_tv) tv[task] = ref_tv[s] - decoded_psnr(cap, psf, x, true, nsr, o);
        const std::lock_guard<std::mutex> lock(progress_mutex);
        if (++scenes_done[k] == ns) {
            ++distances_done;
            if (o.progress) o.progress(distances_done, nd);
        }
    });
    std::vector<DepthRecord> out;
    for (std::size_t k = 0; k < nd; ++k) {
        const double u = distances[k];
        DepthRecord r;
        r.object_distance_m = u;
        r.pixels_per_cell = pixels_per_cell_at(mask.camera, u);
        r.period_px = n * r.pixels_per_cell;
        r.lsi_mismatch_px = n * std::fabs(r.pixels_per_cell - ppc);
        r.wiener_nsr = nsr;
        double w = 0, t = 0;
        for (std::size_t s = 0; s < ns; ++s) {
            w += wiener[k * ns + s];
            t += tv[k * ns + s];
        }
        r.wiener_psnr_loss_db = w / ns;
        if (o.with_tv) r.tv_psnr_loss_db = t / ns;
        out.push_back(r);
    }
    return out;
}

}  // namespace pinmask
