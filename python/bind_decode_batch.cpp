// Batch decoding: decode_batch() is `pinmask decode --batch` on a list: many captures (arrays
// or image/RAW paths) with one PSF and one set of decode() keywords. A mask's PSF is synthesised
// once (not per capture); each capture is then one decode() call with those keywords, so every
// result equals decode() on that capture alone, the way the command's batch gives the same
// bytes as single decodes.
#include <optional>
#include <string>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/mosaic.hpp"
#include "core/image/raw_io.hpp"
#include "design/psf/psf.hpp"
#include "python/common.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

void bind_decode_batch(py::module_& m) {
    m.def(
        "decode_batch",
        [](const py::iterable& captures, const std::optional<std::string>& bayer,
           const py::kwargs& kwargs) {
            const BayerMode mode =
                bayer ? parse_bayer_mode(*bayer, field_ref("bayer")) : BayerMode::kSum2x2;
            if (kwargs.contains("capture"))
                throw InvalidInput(field_ref("capture") +
                                   " is not a keyword of decode_batch: the captures are its first "
                                   "argument");
            py::dict options;
            for (auto item : kwargs) options[item.first] = item.second;
            // One PSF for the batch: a mask's PSF synthesised here once (decode() would
            // synthesise it per capture). A refocus (object_distance) stays with the mask: its
            // exact-geometry PSF depends on each capture's size.
            const bool has_mask = options.contains("mask") && !options["mask"].is_none();
            const bool has_psf = options.contains("psf") && !options["psf"].is_none();
            const bool refocus =
                options.contains("object_distance") && !options["object_distance"].is_none();
            if (has_mask && !has_psf && !refocus) {
                const Mask mk = mask_arg(options["mask"]);
                Plane p;
                {
                    py::gil_scoped_release release;
                    p = mask_psf(mk);
                }
                options["psf"] = to_array(std::move(p));
                options["mask"] = py::none();
                // What decode() reads from a mask's PSF when left to it: one period of a
                // tiling, with no camera background (decode/capture/capture_defaults.hpp).
                if (!options.contains("model")) options["model"] = "cyclic";
                if (!options.contains("background")) options["background"] = "none";
            }
            const py::object decode = py::module_::import("pinmask").attr("decode");
            const py::object fspath = py::module_::import("os").attr("fspath");
            py::list results;
            int index = 0;
            for (const py::handle& c : captures) {
                py::object capture = py::reinterpret_borrow<py::object>(c);
                std::string source = "capture " + std::to_string(index);
                if (py::isinstance<py::str>(c) || py::hasattr(c, "__fspath__")) {
                    source = py::str(fspath(c));
                    LoadedImage li;
                    RawInfo raw;
                    {
                        py::gil_scoped_release release;
                        li = bayer ? read_capture_as_mosaic(source, mode, &raw)
                                   : read_capture(source, mode, &raw);
                    }
                    // One PSF for every capture: a full-resolution PSF for a binned RAW capture
                    // is refused, as decode --batch refuses it (core/image/mosaic.hpp).
                    if (raw.binning == 2 && options.contains("psf") &&
                        py::isinstance<py::array>(options["psf"])) {
                        const py::array psf = options["psf"];  // its shape only: no copy
                        try {
                            // A PSF that is not 2-D is decode()'s to refuse, below.
                            if (psf.ndim() == 2)
                                check_shared_psf_sampling(static_cast<int>(psf.shape(0)),
                                                          static_cast<int>(psf.shape(1)),
                                                          li.image.rows(), li.image.cols(), raw);
                        } catch (const InvalidInput& e) {
                            throw InvalidInput(source + ": " + e.what());
                        }
                    }
                    capture = image_to_array(std::move(li.image));
                }
                py::dict r;
                try {
                    r = decode(capture, **options).cast<py::dict>();
                } catch (py::error_already_set& e) {
                    // Which capture failed, in the message of the same exception type.
                    if (e.matches(PyExc_ValueError) || e.matches(PyExc_RuntimeError)) {
                        const std::string what = py::str(e.value());
                        const bool value = e.matches(PyExc_ValueError);
                        if (value) throw InvalidInput(source + ": " + what);
                        throw RuntimeFailure(source + ": " + what);
                    }
                    throw;
                }
                r["source"] = source;
                results.append(r);
                ++index;
            }
            if (index == 0) throw InvalidInput(field_ref("captures") + ": the list is empty");
            return as_result(results);
        },
        py::arg("captures"), py::arg("bayer") = py::none(),
        R"(Decodes many captures with one PSF and the same settings, as `pinmask decode --batch`:
captures is a list of arrays and/or image paths (TIFF, PNG, JPEG, .npy, or camera RAW by
extension, read as read_image(path, bayer) reads it); every other keyword is decode()'s (psf= or
mask=, method, model, nsr, iters, crop, dark, ...), the same names and defaults. A mask's PSF is
synthesised once for the batch; with object_distance (refocus) it is made per capture, for the
capture's size. Returns one dict per capture, in order: decode()'s result plus source (the path,
or 'capture i'). An error names the capture it came from.)");
}

}  // namespace pinmask::python
