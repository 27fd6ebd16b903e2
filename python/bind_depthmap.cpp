// depthmap(): `pinmask depthmap`'s library pipeline (decode/depthmap/depthmap) from Python: the
// dict of `depthmap --json` plus the maps as numpy arrays (depth_m, confidence, all_in_focus,
// label). The capture is an array (grey; a colour array's channels are averaged, as the command
// does) or an image path; nothing is written.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"
#include "decode/depthmap/depthmap.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/metrics/depth_loss.hpp"
#include "python/common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {
namespace {

py::object finite_or_none(double v) {
    return std::isfinite(v) ? py::object(py::float_(v)) : py::none();
}

Plane grey_of(const Image& im) {
    Plane g = Plane::Zero(im.rows(), im.cols());
    for (const Plane& ch : im.channels) g += ch;
    return g / static_cast<double>(im.n_channels());
}

}  // namespace

void bind_depthmap(py::module_& m) {
    m.def(
        "depthmap",
        [](const py::handle& capture, const py::object& mask, const py::object& from_m,
           const py::object& to_m, const py::object& steps, double nsr, int window, double smooth,
           const py::object& psf_stack) {
            const bool capture_is_path =
                py::isinstance<py::str>(capture) || py::hasattr(capture, "__fspath__");
            const std::string capture_path =
                capture_is_path ? py::str(capture).cast<std::string>() : std::string();
            const Plane grey = grey_of(capture_is_path ? read_image(capture_path).image
                                                       : image_arg(capture, "capture"));
            if (!is_all_finite(grey)) throw invalid_field("capture", "", "holds NaN or Inf");
            check_plane_source(!mask.is_none(), !psf_stack.is_none(), !from_m.is_none(),
                               !to_m.is_none(), !steps.is_none());
            DepthmapOptions d;
            d.wiener_nsr = nsr;
            d.window = window;
            d.smooth = smooth;
            if (window > std::min(grey.rows(), grey.cols()))
                throw invalid_field(field_ref("cost_window"), std::to_string(window),
                                    "must be at most the capture's smaller side");
            Mask mk;
            std::vector<PsfStackPlane> planes;
            if (psf_stack.is_none()) {
                mk = mask_arg(mask);
                d.distances_m = depth_range(length_value(from_m, field_ref("from_m"), false),
                                            length_value(to_m, field_ref("to_m"), true),
                                            steps.is_none() ? 16 : steps.cast<int>());
            } else {
                if (!py::isinstance<py::sequence>(psf_stack) || py::isinstance<py::str>(psf_stack))
                    throw invalid_field(field_ref("psf_stack"), "",
                                        "must be a list of (distance_m, psf array) pairs");
                const auto seq = psf_stack.cast<py::sequence>();
                for (std::size_t k = 0; k < seq.size(); ++k) {
                    const py::object item = seq[k];
                    if (!py::isinstance<py::sequence>(item) || py::len(item) != 2)
                        throw invalid_field(field_ref("psf_stack"), std::to_string(k),
                                            "each plane must be a (distance_m, psf array) pair");
                    const auto pair = item.cast<py::sequence>();
                    const double u = length_value(pair[0], field_ref("psf_stack"), false);
                    planes.push_back({u, plane_arg(pair[1], "psf_stack").take()});
                    d.distances_m.push_back(u);
                }
            }
            DepthmapResult r;
            {
                py::gil_scoped_release release;
                r = psf_stack.is_none() ? depthmap(grey, mk, d) : depthmap(grey, planes, d);
            }
            const bool mask_is_path = !mask.is_none() && (py::isinstance<py::str>(mask) ||
                                                          py::hasattr(mask, "__fspath__"));
            py::dict out;
            out["capture"] = capture_is_path ? py::object(py::str(capture_path)) : py::none();
            out["mask"] = mask_is_path ? py::object(py::str(mask)) : py::none();
            out["psf_stack"] = py::none();  // a list of arrays, not a file
            out["rows"] = r.depth_m.rows();
            out["cols"] = r.depth_m.cols();
            out["planes_planned"] = d.distances_m.size();
            out["planes_done"] = r.distances_m.size();
            out["interrupted"] = r.interrupted;
            out["wiener_nsr"] = nsr;
            out["window_px"] = window;
            out["smooth"] = smooth;
            out["capture_depth_m"] = finite_or_none(r.capture_depth_m);
            out["capture_confidence"] = r.capture_confidence;
            out["capture_evidence_depth_m"] = finite_or_none(r.capture_evidence_depth_m);
            out["depth_min_m"] = finite_or_none(r.depth_min_m);
            out["depth_median_m"] = finite_or_none(r.depth_median_m);
            out["depth_max_m"] = finite_or_none(r.depth_max_m);
            out["confidence_median"] = r.confidence_median;
            py::list planes_out;
            for (std::size_t k = 0; k < r.distances_m.size(); ++k) {
                py::dict p;
                p["object_distance_m"] = finite_or_none(r.distances_m[k]);
                p["pixel_fraction"] = r.plane_fraction[k];
                p["mean_cost"] = r.plane_cost[k];
                p["evidence"] = r.plane_evidence[k];
                planes_out.append(p);
            }
            out["planes"] = planes_out;
            out["files"] = py::list();
            out["depth_m"] = to_array(std::move(r.depth_m));
            out["confidence"] = to_array(std::move(r.confidence));
            out["all_in_focus"] = to_array(std::move(r.all_in_focus));
            out["label"] = to_array(std::move(r.label));
            return as_result(out);
        },
        py::arg("capture"), py::arg("mask") = py::none(), py::arg("from_m") = py::none(),
        py::arg("to_m") = py::none(), py::arg("steps") = py::none(), py::arg("nsr") = 0.01,
        py::arg("window") = 121, py::arg("smooth") = kDepthmapDefaultSmooth,
        py::arg("psf_stack") = py::none(),
        R"(Depth map of one capture as `pinmask depthmap`: a plane sweep over steps (default 16)
distances from from_m to to_m (metres, or strings with a unit as "40cm"; to_m may be inf;
equally spaced in 1/u) with the mask's exact-geometry PSF at each, or over the planes of
psf_stack (a list of (distance_m, psf array)
pairs, measured or computed elsewhere; PSFs at most the capture's size, centred at (rows // 2,
cols // 2); instead of mask, from_m, to_m and steps). Wiener decodes (scalar nsr), cost the local
energy (window x window px box) of the residual capture - PSF (*) estimate; per pixel the plane
minimising the cost plus smooth times a penalty on neighbouring planes' steps (0: the lowest-cost
plane), refined by a parabola in 1/u. capture: a 2-D (or colour, averaged) array or an image
path; mask: a Mask or *.mask.json path. Returns the keys of `pinmask depthmap --json` (files
empty: nothing is written) plus the arrays depth_m (metres), confidence ([0, 1]), all_in_focus
and label (plane index). Method and measured accuracy: docs/depth.md.)");

    m.def(
        "depth_fisher",
        [](const py::handle& mask, double object_distance_m, double photons, double read_noise,
           int rows, int cols) {
            DepthFisherOptions o;
            o.photons = photons;
            o.read_noise_e = read_noise;
            o.rows = rows;
            o.cols = cols;
            const Mask mk = mask_arg(mask);
            DepthFisher f;
            {
                py::gil_scoped_release release;
                f = depth_fisher(mk, object_distance_m, o);
            }
            py::dict out;
            out["object_distance_m"] = f.object_distance_m;
            out["fisher_inverse_m2"] = f.fisher_inverse_m2;
            out["crb_inverse_per_m"] = f.crb_inverse_per_m;
            out["crb_distance_m"] = f.crb_distance_m;
            out["one_pixel_inverse_per_m"] = f.one_pixel_inverse_per_m;
            return as_result(out);
        },
        py::arg("mask"), py::arg("object_distance_m"), py::arg("photons") = 20000.0,
        py::arg("read_noise") = 0.0, py::arg("rows") = 0, py::arg("cols") = 0,
        R"(Depth discriminability of a mask (optimize/metrics/depth_fisher): the Fisher information of
t = 1/u in the capture of a point source on the axis at object_distance_m (photons electrons
over one period, Poisson plus Gaussian read noise, variance mu + read_noise^2), over a
rows x cols window (0: the sensor). Returns fisher_inverse_m2 (I(t), m^2), the Cramer-Rao bounds
crb_inverse_per_m (sigma of 1/u) and crb_distance_m (sigma of u), and one_pixel_inverse_per_m
(w / (f N_t d): one pixel of pattern change in 1/u).)");
}

}  // namespace pinmask::python
