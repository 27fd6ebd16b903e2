#include "decode/depthmap/depthmap_run.hpp"

#include <algorithm>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "optimize/metrics/depth_loss.hpp"

namespace pinmask {

DepthmapReport run_depthmap_request(DepthmapRequest q) {
    const Image& im = q.capture;
    Plane grey = Plane::Zero(im.rows(), im.cols());
    for (const Plane& ch : im.channels) grey += ch;
    grey /= static_cast<double>(im.n_channels());
    if (!is_all_finite(grey)) throw invalid_field("capture", q.capture_name, "holds NaN or Inf");
    if (q.window < 3 || q.window % 2 == 0 || q.window > std::min(grey.rows(), grey.cols())) {
        throw invalid_field(field_ref("cost_window"), std::to_string(q.window),
                            "must be odd, >= 3 and at most the capture's smaller side");
    }
    DepthmapOptions d;
    if (q.mask) {
        d.distances_m = depth_range(q.from_m, q.to_m, q.steps);
    } else {
        for (const PsfStackPlane& p : q.psf_stack) d.distances_m.push_back(p.distance_m);
    }
    d.smooth = q.smooth;
    d.wiener_nsr = q.wiener_nsr;
    d.window = q.window;
    d.stop = q.stop;
    d.progress = q.progress;
    if (q.progress) q.progress(0, d.distances_m.size());  // the sweep starts
    DepthmapReport r;
    r.result = q.mask ? depthmap(grey, *q.mask, d) : depthmap(grey, q.psf_stack, d);
    r.planes_planned = d.distances_m.size();
    r.capture_name = q.capture_name;
    r.mask_name = q.mask_name;
    r.psf_stack_name = q.psf_stack_name;
    r.wiener_nsr = q.wiener_nsr;
    r.window = q.window;
    r.smooth = q.smooth;
    return r;
}

}  // namespace pinmask
