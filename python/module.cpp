// The pinmask Python module: entry point. Each bind_*.cpp adds one concept (python/common.hpp).
#include "python/common.hpp"

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
    m.attr("__version__") = "0.1.0";
    bind_errors(m);
    bind_arrays(m);
    bind_design(m);
    bind_mask(m);
    bind_psf(m);
    bind_simulate(m);
    bind_decode(m);
    bind_metrics(m);
    bind_search(m);
    bind_compare(m);
    bind_export(m);
    bind_check(m);
}
