// Kernels and the PSF of a mask (design/psf/kernel.hpp, design/psf/psf.hpp), PSF files
// (io/psf_files), image files (core/image/image_io). psf() and write_psf() follow `pinmask psf`
// (cli/cmd_psf.cpp).
#include <cctype>
#include <filesystem>
#include <optional>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/image/image_io.hpp"
#include "core/image/mosaic.hpp"
#include "core/image/raw_io.hpp"
#include "core/units/number_format.hpp"
#include "decode/capture/estimate_output.hpp"
#include "design/optics/working_distance.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "design/psf/psf_settings.hpp"
#include "io/psf_files.hpp"
#include "python/common.hpp"
#include "python/keyword_names.hpp"
#include "python/result.hpp"
#include "python/values.hpp"

namespace pinmask::python {

namespace {

// The mask with `pinmask psf --kernel/--kernel-path` applied (the same checks and messages,
// naming the keywords).
Mask with_kernel(Mask mask, const std::optional<std::string>& kernel,
                 const std::string& kernel_path) {
    const std::string k = kernel.value_or("");
    if (!k.empty()) parse_kernel_model(k, field_ref("kernel"));
    check_kernel_settings(k, kernel_path);
    if (!k.empty()) {
        mask.psf.kernel.model = k;
        mask.psf.kernel.measured_path = kernel_path;
    }
    return mask;
}

// write_image(): a PNG scaled by decode's rule (decode/capture/estimate_output scale_for_png) when
// `scale` is given, and otherwise refused when a value lies outside [0, 1], where write_png would
// clamp it silently (a decode in capture units came out all white).
void write_image_scaled(const std::filesystem::path& path, Image img, const py::object& scale,
                        int bits) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool png = ext == ".png";
    if (!png && ext != ".tif" && ext != ".tiff" && ext != ".npy") {
        write_image(path, img);  // refuses the extension, naming it
        return;
    }
    if (!scale.is_none() && !png)
        throw invalid_field(field_ref("scale"), py::str(py::repr(scale)).cast<std::string>(),
                            "applies to .png only: .tif/.tiff and .npy hold the values as "
                            "they are");
    if (bits != 8 && bits != 16)
        throw invalid_field(field_ref("bits"), std::to_string(bits), "must be 8 or 16");
    if (!png) {
        write_image(path, img);
        return;
    }
    if (!scale.is_none()) {
        std::optional<double> factor;
        if (py::isinstance<py::str>(scale)) {
            if (scale.cast<std::string>() != "max")
                throw invalid_field(field_ref("scale"), scale.cast<std::string>(),
                                    "must be 'max' or a factor > 0");
        } else {
            const auto refuse = [&] {
                return py::type_error(py_names::spell_keywords(
                    field_ref("scale") + " must be 'max' or a number, not " +
                    std::string(py::str(scale.get_type().attr("__name__")))));
            };
            if (py::isinstance<py::bool_>(scale)) throw refuse();
            try {
                factor = py::float_(scale).cast<double>();  // numpy scalars too
            } catch (const py::error_already_set&) {
                throw refuse();
            }
            if (!(*factor > 0.0) || !std::isfinite(*factor))
                throw invalid_field(field_ref("scale"), format_number(*factor),
                                    "must be 'max' or a finite factor > 0");
        }
        for (const Plane& ch : img.channels)
            if (!is_all_finite(ch)) throw invalid_field(field_ref("image"), "", "holds NaN or Inf");
        img = scale_for_png(img, factor).image;
    } else {
        double lo = 0.0, hi = 0.0;
        bool finite = true;
        for (const Plane& ch : img.channels) {
            if (ch.size() == 0) continue;
            finite = finite && is_all_finite(ch);
            lo = std::min(lo, ch.minCoeff());
            hi = std::max(hi, ch.maxCoeff());
        }
        if (!finite || lo < 0.0 || hi > 1.0)
            throw invalid_field(
                field_ref("image"),
                finite ? "values in [" + format_number(lo) + ", " + format_number(hi) + "]"
                       : std::string("NaN or Inf"),
                "a PNG holds [0, 1] and would clip them: give scale='max' (what `pinmask "
                "decode -o x.png` writes: negatives to 0, divided by the largest value) or "
                "scale=FACTOR, divide the array yourself, or write .tiff or .npy for the raw "
                "values");
    }
    write_png(path, img, bits);
}

struct PsfAndKernel {
    Plane psf;
    Kernel kernel;
};

PsfAndKernel make_psf(const Mask& mask, double energy_fraction) {
    KernelOptions ko;
    ko.energy_fraction = energy_fraction;
    const int ppc = mask.psf.pixels_per_cell;
    check_psf_memory(mask.pattern.n, ppc, 2, 0);
    PsfAndKernel r;
    r.kernel = mask_kernel(mask, ko);
    r.psf = synthesize_psf(mask.pattern, r.kernel, ppc);
    return r;
}

py::dict sidecar_dict(const io::PsfSidecar& s) {
    py::dict d;
    d["mask_geometry_hash"] = s.mask_geometry_hash;
    d["mask_file"] = s.mask_file;
    d["grid_n"] = s.grid_n;
    d["pixels_per_cell"] = s.pixels_per_cell;
    d["pixel_pitch_m"] = s.pixel_pitch_m;
    d["kernel_model"] = s.kernel_model;
    d["kernel_reason"] = s.kernel_reason;
    d["wavelengths"] = s.wavelengths;
    d["kernel_enclosed_energy"] = s.kernel_enclosed_energy;
    d["kernel_support_capped"] = s.kernel_support_capped;
    d["kernel_support_px"] = py::make_tuple(s.kernel_rows, s.kernel_cols);
    d["normalisation"] = s.normalisation;
    d["size_px"] = py::make_tuple(s.rows, s.cols);
    d["tiff_file"] = s.tiff_file;
    d["npy_file"] = s.npy_file;
    return d;
}

}  // namespace

void bind_psf(py::module_& m) {
    py::class_<Kernel>(m, "Kernel",
                       "The single-pinhole kernel on the sensor's pixel grid (sum 1). `values` "
                       "is a writable view of the kernel's own buffer (no copy).")
        .def_property_readonly(
            "values",
            [](py::object self) {
                Kernel& k = self.cast<Kernel&>();
                const py::ssize_t r = k.values.rows(), c = k.values.cols();
                return py::array_t<double>({r, c}, {c * 8, py::ssize_t{8}}, k.values.data(), self);
            })
        .def_readonly("origin_row", &Kernel::origin_row,
                      "pixel row of values[0, 0], counted from the cell's top-left pixel")
        .def_readonly("origin_col", &Kernel::origin_col)
        .def_property_readonly(
            "model", [](const Kernel& k) { return kernel_model_name(k.model); },
            "resolved model (never auto)")
        .def_readonly("model_reason", &Kernel::model_reason)
        .def_readonly("enclosed_energy", &Kernel::enclosed_energy,
                      "continuous energy kept before normalising (0..1)")
        .def_readonly("support_capped", &Kernel::support_capped)
        .def_readonly("wavelengths", &Kernel::wavelengths, "[(wavelength_m, weight)] used");

    m.def(
        "kernel",
        [](const Mask& mask, double energy_fraction) {
            KernelOptions ko;
            ko.energy_fraction = energy_fraction;
            py::gil_scoped_release release;
            return mask_kernel(mask, ko);
        },
        py::arg("mask"), py::arg("energy_fraction") = KernelOptions{}.energy_fraction,
        "The mask's single-pinhole kernel (support capped at the period). energy_fraction: "
        "per-axis energy of the continuous profile the support keeps, in (0, 1].");

    m.def(
        "psf",
        [](const Mask& mask, std::optional<std::string> kernel, const std::string& kernel_path,
           double energy_fraction, const std::string& geometry, const py::object& object_distance,
           std::optional<std::pair<int, int>> size) {
            // As `pinmask psf`: the same checks in the same order, the keyword named.
            if (!(energy_fraction > 0.0 && energy_fraction <= 1.0))
                throw invalid_field(
                    field_ref("energy_fraction"), std::to_string(energy_fraction),
                    "must be in (0, 1]: the fraction of the kernel's energy its support keeps");
            if (geometry != "integer" && geometry != "exact")
                throw invalid_field(field_ref("geometry"), geometry, "must be integer or exact");
            const bool exact = geometry == "exact";
            if (!exact && (!object_distance.is_none() || size)) {
                throw invalid_field(
                    field_ref(size ? "size" : "object_distance"),
                    size ? std::to_string(size->first) + "x" + std::to_string(size->second)
                         : std::string(py::str(object_distance)),
                    "only used with geometry='exact' (the integer model is one period at the "
                    "mask's pixels per cell)");
            }
            const Mask mk = with_kernel(mask, kernel, kernel_path);
            KernelOptions ko;
            ko.energy_fraction = energy_fraction;
            if (!exact) {
                Plane psf;
                {
                    py::gil_scoped_release release;
                    psf = make_psf(mk, energy_fraction).psf;
                }
                return to_array(std::move(psf));
            }
            // design/psf/psf_exact: what the sensor records from a point at object_distance
            // (default the mask's u), over the sensor or size = (rows, cols).
            ExactPsfOptions eo;
            eo.kernel = ko;
            eo.object_distance_m = object_distance.is_none()
                                       ? mk.camera.object_distance_m
                                       : length_value(object_distance, "object_distance", true);
            check_object_distance(mk.camera, eo.object_distance_m, "object_distance");
            if (size) {
                eo.rows = size->first;
                eo.cols = size->second;
            }
            Plane psf;
            {
                py::gil_scoped_release release;
                psf = exact_psf(mk, eo);
            }
            return to_array(std::move(psf));
        },
        py::arg("mask"), py::arg("kernel") = py::none(), py::arg("kernel_path") = "",
        py::arg("energy_fraction") = KernelOptions{}.energy_fraction,
        py::arg("geometry") = "integer", py::arg("object_distance") = py::none(),
        py::arg("size") = py::none(),
        "The PSF as `pinmask psf` computes it (kernel: override the mask's model). geometry "
        "'integer' (default): the decoder's model, one period, (n ppc) x (n ppc) float64, sum 1. "
        "'exact': what the sensor records from a point at object_distance (metres or a string "
        "with a unit, '2m', 'inf'; default the mask's u): every pinhole of the tiled mask at its "
        "true sub-pixel position, pitch d (1 - f/f' + f/u) / w pixels, over the sensor or size "
        "= (rows, cols) pixels. The array owns the library's buffer (no copy).");

    m.def(
        "write_psf",
        [](const Mask& mask, const std::filesystem::path& path, bool npy,
           const std::string& mask_file, std::optional<std::string> kernel,
           const std::string& kernel_path, double energy_fraction) {
            const std::string ext = path.extension().string();
            if (ext != ".tif" && ext != ".tiff")
                throw invalid_field("-o", path.string(), "must end in .tif or .tiff");
            const Mask mk = with_kernel(mask, kernel, kernel_path);
            std::vector<std::filesystem::path> written;
            {
                py::gil_scoped_release release;
                const PsfAndKernel pk = make_psf(mk, energy_fraction);
                written = io::write_psf_files(path, pk.psf,
                                              io::psf_sidecar_for(mk, pk.kernel, mask_file), npy);
            }
            std::vector<std::string> out;
            for (const auto& p : written) out.push_back(p.string());
            return out;
        },
        py::arg("mask"), py::arg("path"), py::arg("npy") = false, py::arg("mask_file") = "",
        py::arg("kernel") = py::none(), py::arg("kernel_path") = "",
        py::arg("energy_fraction") = KernelOptions{}.energy_fraction,
        "Writes the PSF files of `pinmask psf MASK -o path [--npy]`: float32 TIFF (+ .npy) and "
        "the JSON sidecar, all or nothing; mask_file is recorded in the sidecar (the CLI records "
        "the mask path it was given). Returns the paths written.");

    m.def(
        "read_psf",
        [](const std::filesystem::path& path) {
            io::PsfFile f = io::read_psf_file(path);
            py::object side =
                f.sidecar ? py::object(as_result(sidecar_dict(*f.sidecar))) : py::none();
            return py::make_tuple(to_array(std::move(f.psf)), side);
        },
        py::arg("path"),
        "(psf, sidecar) of a PSF image (TIFF/PNG/npy) and its JSON sidecar (None when absent); "
        "the PSF renormalised to sum 1, as the decoder reads it.");

    m.def(
        "read_image",
        [](const std::filesystem::path& path, const std::optional<std::string>& bayer) {
            // None: RAW files as sum2x2, other files as they are; given: any file as a mosaic
            // (`decode --bayer` given, core/image/mosaic.hpp).
            const BayerMode mode =
                bayer ? parse_bayer_mode(*bayer, field_ref("bayer")) : BayerMode::kSum2x2;
            LoadedImage li;
            {
                py::gil_scoped_release release;
                li = bayer ? read_capture_as_mosaic(path, mode) : read_capture(path, mode);
            }
            return py::make_tuple(image_to_array(std::move(li.image)), li.full_scale);
        },
        py::arg("path"), py::arg("bayer") = py::none(),
        "(image, full_scale) of a TIFF, PNG, JPEG or .npy file (by content), or of a camera RAW "
        "file (by extension: .dng, .cr2, .nef, .arw, ...; through LibRaw, black level removed) as "
        "`decode` and `calibrate` read captures: raw values (integer files as counts, full_scale "
        "= 255 or 65535; float files 1.0; RAW: white - black). Grey: (rows, cols), no copy; "
        "colour: (rows, cols, 3). bayer (as --bayer; None: 'sum2x2' for RAW, nothing for other "
        "files): 'sum2x2' (each 2 x 2 Bayer cell summed: half the resolution, pixel pitch "
        "doubled) | 'green' ('g') | 'r' | 'b' (one colour's sites). Given with a TIFF, PNG or "
        ".npy, the file is a single-channel mosaic: sum2x2 applies, green/r/b (no colour-filter "
        "pattern in the file) and colour images raise ValueError.");
    m.def(
        "write_image",
        [](const std::filesystem::path& path, const py::handle& image, const py::object& scale,
           int bits) {
            Image img = image_arg(image, "image");
            write_image_scaled(path, std::move(img), scale, bits);
        },
        py::arg("path"), py::arg("image"), py::arg("scale") = py::none(), py::arg("bits") = 16,
        "Writes by extension: .tif/.tiff (float32) and .npy (float32) hold the values as they "
        "are; .png (bits 8 or 16, default 16) holds [0, 1]. scale (PNG only) is decode's "
        "--scale: 'max' (negatives to 0, then divided by the largest value over all channels: "
        "what `pinmask decode -o x.png` writes, with bits=8 for its default --bits) or a factor "
        "> 0 (negatives to 0, multiplied, above 1 full white); None (default): the values are "
        "written as they are and must lie in [0, 1] (ValueError otherwise, saying how to scale: "
        "a decode or a capture in counts would come out white). Atomic. 2-D: grey; 3-D (rows, "
        "cols, channels).");
}

}  // namespace pinmask::python
