// depthmap(): `pinmask depthmap`'s library transaction (decode/depthmap/depthmap_run) from Python:
// io/depthmap_json's dict (`depthmap --json`) plus the maps as numpy arrays (depth_m, confidence,
// all_in_focus, label). The capture is an array (grey; a colour array's channels are averaged, as
// the command does) or an image path; with output_dir the command's files are written there.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io.hpp"
#include "decode/depthmap/depthmap_run.hpp"
#include "io/depthmap_json.hpp"
#include "optimize/metrics/depth_fisher.hpp"
#include "optimize/metrics/depth_loss.hpp"
#include "python/background_arg.hpp"
#include "python/common.hpp"
#include "python/json_value.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

void bind_depthmap(py::module_& m) {
    m.def(
        "depthmap",
        [](const py::handle& capture, const py::object& mask, const py::object& from_m,
           const py::object& to_m, const py::object& steps, double nsr, int window, double smooth,
           const py::object& psf_stack, const py::handle& background, int downsample,
           const std::optional<std::string>& output_dir) {
            if (output_dir) check_output_folder(*output_dir, field_ref("output_dir"));
            DepthmapRequest q;
            const bool capture_is_path =
                py::isinstance<py::str>(capture) || py::hasattr(capture, "__fspath__");
            if (capture_is_path) q.capture_name = py::str(capture).cast<std::string>();
            q.capture =
                capture_is_path ? read_image(q.capture_name).image : image_arg(capture, "capture");
            check_plane_source(!mask.is_none(), !psf_stack.is_none(), !from_m.is_none(),
                               !to_m.is_none(), !steps.is_none());
            q.capture_options.background = background_arg(background);
            q.capture_options.downsample = downsample;
            q.wiener_nsr = nsr;
            q.window = window;
            q.smooth = smooth;
            if (psf_stack.is_none()) {
                q.mask = mask_arg(mask);
                if (py::isinstance<py::str>(mask) || py::hasattr(mask, "__fspath__"))
                    q.mask_name = py::str(mask).cast<std::string>();
                if (!from_m.is_none()) q.from_m = length_value(from_m, field_ref("from_m"), false);
                if (!to_m.is_none()) q.to_m = length_value(to_m, field_ref("to_m"), true);
                if (!steps.is_none()) q.steps = steps.cast<int>();
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
                    q.psf_stack.push_back({u, plane_arg(pair[1], "psf_stack").take()});
                }
            }
            DepthmapReport r;
            {
                py::gil_scoped_release release;
                r = run_depthmap_request(std::move(q));
                if (output_dir) io::write_depthmap_files(r, *output_dir);
            }
            // depthmap --json's dict, then the maps.
            py::dict out = json_value(io::depthmap_json(r));
            out["depth_m"] = to_array(std::move(r.result.depth_m));
            out["confidence"] = to_array(std::move(r.result.confidence));
            out["cost_margin"] = to_array(std::move(r.result.cost_margin));
            out["all_in_focus"] = to_array(std::move(r.result.all_in_focus));
            out["label"] = to_array(std::move(r.result.label));
            return as_result(out);
        },
        py::arg("capture"), py::arg("mask") = py::none(), py::arg("from_m") = py::none(),
        py::arg("to_m") = py::none(), py::arg("steps") = py::none(),
        py::arg("nsr") = DepthmapRequest{}.wiener_nsr, py::arg("window") = DepthmapRequest{}.window,
        py::arg("smooth") = DepthmapRequest{}.smooth, py::arg("psf_stack") = py::none(),
        py::arg("background") = "none", py::arg("downsample") = 0,
        py::arg("output_dir") = py::none(),
        R"(Depth map of one capture as `pinmask depthmap`: a plane sweep over steps distances from
from_m to to_m (metres, or strings with a unit as "40cm"; to_m may be inf; equally spaced in 1/u;
None: from_m and to_m the design's usable object distances, steps one resolvable depth step
apart, at most 64; the result's "sweep" says what was chosen and the depth resolution) with the
mask's exact-geometry PSF at each, or over the planes of
psf_stack (a list of (distance_m, psf array)
pairs, measured or computed elsewhere; PSFs at most the capture's size, centred at (rows // 2,
cols // 2); instead of mask, from_m, to_m and steps). Wiener decodes (scalar nsr), cost the local
energy (window x window px box) of the residual capture - PSF (*) estimate; per pixel the plane
minimising the cost plus smooth times a penalty on neighbouring planes' steps (0: the lowest-cost
plane), refined by a parabola in 1/u. capture: a 2-D (or colour, averaged) array or an image
path; mask: a Mask or *.mask.json path. background: 'none', 'corner' (each image's own mean of
rows/cols 5..14 off it: the capture's, and each psf_stack PSF's, clipped at 0) or a number of
counts off the capture; downsample: K rounds of 2x2 box averaging of the capture and the PSFs (a
mask's PSFs drawn at the binned pixel pitch). output_dir: write the command's files there
(depth.tif, confidence.tif, cost_margin.tif, all_in_focus.tif, depthmap.png, depthmap.json; all
or none); None writes nothing. Returns what `pinmask depthmap --json` prints (files: those
written, [] without output_dir) plus the arrays depth_m (metres), confidence (the probability
that the depth lies within one plane spacing, mapped from the cost margin), cost_margin
((median cost - chosen cost) / median cost), all_in_focus and label (plane index). Method and
measured accuracy: docs/depth.md.)");

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
