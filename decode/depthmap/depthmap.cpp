#include "decode/depthmap/depthmap.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "decode/depthmap/calibrated_confidence.hpp"
#include "decode/depthmap/refine.hpp"
#include "decode/depthmap/smooth_labels.hpp"
#include "decode/depthmap/sweep_cost.hpp"
#include "design/optics/distance_list.hpp"
#include "design/optics/working_distance.hpp"

namespace pinmask {
namespace {

constexpr std::size_t kMaxPlanes = 1000;

template <class CostAt>
DepthmapResult run(const Plane& capture, const std::vector<double>& u, const DepthmapOptions& o,
                   CostAt cost_at) {
    // Costs and estimates of every plane, the smoothing's four volumes (the costs by pixel, the
    // path costs, the sums, the aggregate returned), plus the working set of one plane.
    const double volumes = o.smooth > 0.0 ? 6.0 : 2.0;
    check_memory((volumes * double(u.size()) + 12.0) * double(capture.size()) * 8.0,
                 "the depth map's " + std::to_string(u.size()) + " planes");
    std::vector<Plane> costs, estimates;
    DepthmapResult out;
    for (std::size_t k = 0; k < u.size(); ++k) {
        if (o.stop && o.stop->load() && k >= 1) {
            out.interrupted = true;
            break;
        }
        PlaneCost pc = cost_at(k);
        out.plane_evidence.push_back(pc.evidence);
        costs.push_back(std::move(pc.cost));
        estimates.push_back(std::move(pc.estimate));
        out.distances_m.push_back(u[k]);
        if (o.progress) o.progress(k + 1, u.size());
    }
    std::vector<double> inv;
    for (double d : out.distances_m) inv.push_back(std::isinf(d) ? 0.0 : 1.0 / d);
    std::vector<Plane> means;
    for (const Plane& c : costs) {
        out.plane_cost.push_back(c.mean());
        means.push_back(Plane::Constant(1, 1, c.mean()));
    }
    const RefinedDepth whole = refine_depth(means, inv);
    out.capture_depth_m = whole.depth_m(0, 0);
    out.capture_confidence = whole.confidence(0, 0);
    std::vector<Plane> evidence;
    for (double e : out.plane_evidence) evidence.push_back(Plane::Constant(1, 1, e));
    out.capture_evidence_depth_m = refine_depth(evidence, inv).depth_m(0, 0);
    const double scale = o.smooth > 0.0 ? o.smooth * cost_well_depth(costs) : 0.0;
    RefinedDepth r;
    if (scale > 0.0) {
        // The labels and the sub-plane parabola from the aggregated costs; the confidence from
        // the sweep's own costs at the chosen plane.
        r = refine_depth(aggregate_paths(costs, scale, 2.0 * scale, 8), inv);
        r.confidence = label_confidence(costs, r.label);
    } else {
        r = refine_depth(costs, inv);
    }
    out.depth_m = std::move(r.depth_m);
    out.confidence = calibrated_confidence(r.confidence);
    out.cost_margin = std::move(r.confidence);
    out.label = std::move(r.label);
    out.all_in_focus = Plane(capture.rows(), capture.cols());
    out.plane_fraction.assign(out.distances_m.size(), 0.0);
    for (Eigen::Index i = 0; i < capture.rows(); ++i) {
        for (Eigen::Index j = 0; j < capture.cols(); ++j) {
            const auto k = static_cast<std::size_t>(out.label(i, j));
            out.all_in_focus(i, j) = estimates[k](i, j);
            out.plane_fraction[k] += 1.0 / double(capture.size());
        }
    }
    auto median = [](const Plane& p) {
        std::vector<double> v(p.data(), p.data() + p.size());
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    };
    out.depth_min_m = out.depth_m.minCoeff();
    out.depth_max_m = out.depth_m.maxCoeff();
    out.depth_median_m = median(out.depth_m);
    out.confidence_median = median(out.confidence);
    return out;
}

}  // namespace

void DepthmapOptions::validate_settings() const {
    if (!(wiener_nsr > 0.0) || !std::isfinite(wiener_nsr)) {
        throw invalid_field(field_ref("wiener_nsr"), std::to_string(wiener_nsr),
                            "must be finite and > 0");
    }
    if (window < 3 || window % 2 == 0) {
        throw invalid_field(field_ref("cost_window"), std::to_string(window),
                            "must be odd and >= 3");
    }
    if (!(smooth >= 0.0) || !std::isfinite(smooth)) {
        throw invalid_field(field_ref("smooth"), format_number(smooth),
                            "must be finite and >= 0 (0: the lowest-cost plane per pixel)");
    }
}

void check_plane_source(bool mask, bool psf_stack, bool from, bool to, bool steps) {
    if (mask == psf_stack) {
        throw invalid_field(field_ref("mask"), mask ? "given" : "absent",
                            "give either " + field_ref("mask") + " (with " + field_ref("from_m") +
                                ", " + field_ref("to_m") + " and " + field_ref("steps") +
                                " optional) or " + field_ref("psf_stack") + ", one of them");
    }
    if (psf_stack) {
        for (const auto& [name, given] :
             {std::pair<const char*, bool>{"from_m", from}, {"to_m", to}, {"steps", steps}}) {
            if (given) {
                throw invalid_field(field_ref(name), "given",
                                    "not with " + field_ref("psf_stack") +
                                        ": the stack's distances are the planes");
            }
        }
    }
}

void DepthmapOptions::validate() const {
    if (distances_m.size() < 2 || distances_m.size() > kMaxPlanes) {
        throw invalid_field(field_ref("distances_m"), std::to_string(distances_m.size()),
                            "need between 2 and 1000 planes");
    }
    validate_settings();
}

DepthmapResult depthmap(const Plane& capture, const Mask& mask, const DepthmapOptions& o) {
    o.validate();
    std::vector<double> u = o.distances_m;
    for (double d : u) check_object_distance(mask.camera, d, "distances_m");
    check_distinct_distances(u, field_ref("distances_m"));
    std::sort(u.begin(), u.end());
    return run(capture, u, o, [&](std::size_t k) {
        return sweep_cost(capture, mask, u[k], o.wiener_nsr, o.window);
    });
}

DepthmapResult depthmap(const Plane& capture, const std::vector<PsfStackPlane>& stack,
                        const DepthmapOptions& o) {
    o.validate_settings();
    if (stack.size() < 2 || stack.size() > kMaxPlanes) {
        throw invalid_field(field_ref("psf_stack"), std::to_string(stack.size()) + " planes",
                            "need between 2 and 1000 planes");
    }
    std::vector<std::size_t> order(stack.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const double d = stack[k].distance_m;
        if (!(d > 0.0) || !std::isfinite(d)) {
            throw invalid_field(field_ref("psf_stack"), format_number(d),
                                "plane " + std::to_string(k) +
                                    ": the object distance must be finite and > 0 (metres)");
        }
        const Plane& h = stack[k].psf;
        if (h.rows() < 1 || h.cols() < 1 || h.rows() > capture.rows() ||
            h.cols() > capture.cols()) {
            throw invalid_field(
                field_ref("psf_stack"), std::to_string(h.rows()) + "x" + std::to_string(h.cols()),
                "plane " + std::to_string(k) + ": a PSF must be at most the capture's size (" +
                    std::to_string(capture.rows()) + "x" + std::to_string(capture.cols()) + ")");
        }
        // One camera's stack: every plane the size of the first (the command's reader refuses
        // a listing that differs; an array stack from Python met no check before).
        if (k > 0 && (h.rows() != stack[0].psf.rows() || h.cols() != stack[0].psf.cols())) {
            throw invalid_field(
                field_ref("psf_stack"), std::to_string(h.rows()) + "x" + std::to_string(h.cols()),
                "plane " + std::to_string(k) + " differs from plane 0's " +
                    std::to_string(stack[0].psf.rows()) + "x" +
                    std::to_string(stack[0].psf.cols()) + " (one camera's stack has one size)");
        }
        if (!is_all_finite(h) || h.minCoeff() < 0.0 || !(h.sum() > 0.0)) {
            throw invalid_field(field_ref("psf_stack"), "",
                                "plane " + std::to_string(k) +
                                    ": a PSF must be finite, non-negative and hold some light");
        }
        order[k] = k;
    }
    std::vector<double> given;
    for (const PsfStackPlane& p : stack) given.push_back(p.distance_m);
    check_distinct_distances(given, field_ref("psf_stack"));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return given[a] < given[b]; });
    std::vector<double> u;
    for (std::size_t k : order) u.push_back(stack[k].distance_m);
    return run(capture, u, o, [&](std::size_t k) {
        return sweep_cost(capture, stack[order[k]].psf, o.wiener_nsr, o.window);
    });
}

}  // namespace pinmask
