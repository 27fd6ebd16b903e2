// The robust-design set-up of test_robust_search and test_robust_floor: the paper camera on a
// 16 x 16 grid, 8 px per cell, box kernel, K = 20, Gaussian 50 dB, an 8-scene prior, one chain of
// 4000 evaluations (restarts of 2000) with seed 3; and the errors: +-10 % pinhole side (44 um of
// the paper's 440 um) and 2 um position jitter.
#pragma once

#include "design/optics/camera.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/search/search_pipeline.hpp"

namespace pinmask::test {

inline SearchPipelineOptions robust_camera_options() {
    SearchPipelineOptions o;
    o.tmpl.camera = paper_camera();
    o.tmpl.pattern.n = 16;
    o.tmpl.psf.pixels_per_cell = 8;
    o.tmpl.psf.kernel.model = "box";
    o.holes = 20;
    o.search.threads = 1;
    o.search.time_budget_s = 0.0;
    o.search.max_evaluations = 4000;
    o.search.anneal_restart_moves = 2000;
    o.search.seed = 3;
    o.search.top = 1;
    o.noise.snr_db = 50.0;  // the error is visible above the noise
    o.prior.count = 8;
    return o;
}

inline FabricationErrors ten_percent_errors() {
    FabricationErrors e;
    e.size_bias_m = 44e-6;  // 10 % of the paper's 440 um pinhole side
    e.jitter_m = 2e-6;
    return e;
}

}  // namespace pinmask::test
