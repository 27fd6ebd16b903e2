#include "decode/depthmap/depthmap_run.hpp"

#include <algorithm>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "optimize/metrics/depth_loss.hpp"

namespace pinmask {

DepthmapReport run_depthmap_request(DepthmapRequest q) {
    PreparedDepthCapture prepared = prepare_depth_capture(
        q.capture, q.capture_options, q.mask ? &*q.mask : nullptr, q.mask ? nullptr : &q.psf_stack);
    const Plane& grey = prepared.capture;
    if (!is_all_finite(grey)) throw invalid_field("capture", q.capture_name, "holds NaN or Inf");
    if (q.window < 3 || q.window % 2 == 0 || q.window > std::min(grey.rows(), grey.cols())) {
        throw invalid_field(field_ref("cost_window"), std::to_string(q.window),
                            "must be odd, >= 3 and at most the capture's smaller side");
    }
    DepthmapOptions d;
    DepthmapReport r;
    if (q.mask) {
        r.planes =
            choose_depthmap_planes(*q.mask, q.from_m, q.to_m, q.steps,
                                   static_cast<int>(grey.rows()), static_cast<int>(grey.cols()));
        d.distances_m = depth_range(r.planes->from_m, r.planes->to_m, r.planes->steps);
    } else {
        for (const PsfStackPlane& p : q.psf_stack) d.distances_m.push_back(p.distance_m);
    }
    d.smooth = q.smooth;
    d.wiener_nsr = q.wiener_nsr;
    d.window = q.window;
    d.stop = q.stop;
    d.progress = q.progress;
    if (q.progress) q.progress(0, d.distances_m.size());  // the sweep starts
    r.result = q.mask ? depthmap(grey, *q.mask, d) : depthmap(grey, q.psf_stack, d);
    r.planes_planned = d.distances_m.size();
    r.capture_name = q.capture_name;
    r.mask_name = q.mask_name;
    r.psf_stack_name = q.psf_stack_name;
    r.wiener_nsr = q.wiener_nsr;
    r.window = q.window;
    r.smooth = q.smooth;
    r.capture_options = q.capture_options;
    r.background = prepared.background;
    return r;
}

}  // namespace pinmask
