// The pinmask Python module: entry point. Each bind_*.cpp adds one concept (python/common.hpp).
#include "core/fft/fft_environment.hpp"
#include "core/limits/allocator.hpp"
#include "core/version.hpp"
#include "python/common.hpp"
#include "python/result.hpp"

namespace pinmask::python {
void bind_depth(py::module_& m);         // python/bind_depth.cpp
void bind_depthmap(py::module_& m);      // python/bind_depthmap.cpp
void bind_score(py::module_& m);         // python/bind_score.cpp
void bind_decode_batch(py::module_& m);  // python/bind_decode_batch.cpp
void bind_sweep(py::module_& m);         // python/bind_sweep.cpp
}  // namespace pinmask::python

PYBIND11_MODULE(pinmask, m) {
    using namespace pinmask::python;
    m.doc() = R"(pinmask: coded pinhole-array masks for a coded pinhole lens camera.

The libraries of the `pinmask` command line, from Python: optics numbers, masks (generate, load,
save), PSFs, simulation, decoding, metrics, search, comparison reports, fabrication export and
the design-rule check. Units are SI (metres, seconds) unless a name says otherwise.

Arrays: numpy in and out. Returned arrays wrap the library's own buffers (no copy); grey images
are (rows, cols) float64, colour images (rows, cols, channels) (interleaved once). Inputs:
decode() uses a module-made mono capture and PSF as they are (is_library_buffer() says which
arrays qualify); every other float32/float64 array (any order) is copied once into the
library's row-major double planes; other dtypes are converted first. input_copies() counts
the input copies made.

Errors: ValueError for invalid input (the message is the command line's: it names the flag or
field, the value and the rule), RuntimeError for failures while doing valid work.)";
    m.attr("__version__") = pinmask::kVersion;
    // core/limits/allocator.hpp: freed planes stay on the heap (up to 32 MiB), so repeated decodes
    // do not page-fault their memory in again; PINMASK_ALLOCATOR=default before import skips it.
    pinmask::keep_freed_memory();
    // The command's FFT planning (core/fft/fft_environment): measured plans from the same wisdom
    // file ($PINMASK_WISDOM, $XDG_CACHE_HOME/pinmask/wisdom, ~/.cache/pinmask/wisdom), so the
    // module's transforms are the command's (same plans, same bits) and as fast. Its warnings
    // (a corrupt or foreign file, ignored and replaced) go to Python's warnings.
    for (const std::string& w : pinmask::configure_fft_from_environment())
        if (PyErr_WarnEx(PyExc_RuntimeWarning, ("pinmask: " + w).c_str(), 1) < 0)
            throw pybind11::error_already_set();
    bind_errors(m);
    bind_result(m);
    bind_arrays(m);
    bind_design(m);
    bind_mask(m);
    bind_psf(m);
    bind_simulate(m);
    bind_decode(m);
    bind_decode_batch(m);
    bind_metrics(m);
    bind_score(m);
    bind_search(m);
    bind_sweep(m);
    bind_compare(m);
    bind_export(m);
    bind_check(m);
    bind_calibrate(m);
    bind_depth(m);
    bind_depthmap(m);
}
