// Shared plumbing of the pinmask Python module: numpy <-> Plane conversion, the error mapping,
// running long library calls with Ctrl-C and progress callbacks, and the bind_* entry points
// (one binding file per concept; python/module.cpp calls them in order).
//
// Copies (documented in the module docstring and docs/python.md):
//   - out: every array the module returns wraps the library's own buffer (a Plane moved into a
//     capsule that owns it): no copy. Grey images are 2-D (rows, cols); a colour image is
//     (rows, cols, channels) and is interleaved once (the library keeps one plane per channel).
//   - in: where a library function takes a plane (decode's mono capture and PSF), an array the
//     module returned (base = its "pinmask.Plane" capsule, the whole buffer, float64, C order)
//     is handed to it as is: no copy. Any other float32/float64 array, in any order, is copied
//     once into a row-major double plane (the library's functions take owning planes and
//     images); other dtypes are converted by numpy first. input_copies() counts the copies.
#pragma once

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <functional>
#include <string>

#include "core/image/image.hpp"
#include "python/path_caster.hpp"

namespace pinmask::python {

namespace py = pybind11;

// Name of the capsule that owns a library Plane behind a returned array.
inline constexpr const char* kPlaneCapsule = "pinmask.Plane";

// A Plane as a float64 (rows, cols) array that owns it (moved, not copied).
py::array_t<double> to_array(Plane&& plane);
py::array_t<double> to_array(const Plane& plane);  // copies once (for shared library data)
// An Image: one channel -> to_array of it; several -> (rows, cols, channels), copied once.
py::array image_to_array(Image&& image);

// A plane argument: borrowed from a module-made array (no copy) or copied once.
class PlaneArg {
  public:
    const Plane& get() const { return borrowed_ != nullptr ? *borrowed_ : owned_; }
    bool borrowed() const { return borrowed_ != nullptr; }
    // The plane for a consumer that keeps it: the owned copy moved out (get() is then empty),
    // or a copy of a borrowed plane.
    Plane take() { return borrowed_ != nullptr ? Plane(*borrowed_) : std::move(owned_); }

  private:
    friend PlaneArg plane_arg(const py::handle& obj, const std::string& what);
    const Plane* borrowed_ = nullptr;
    Plane owned_;
    py::object keep_;  // the array a borrowed plane lives in
};

// obj must be a 2-D array-like (ValueError naming `what` otherwise).
PlaneArg plane_arg(const py::handle& obj, const std::string& what);
// 2-D -> one channel; 3-D (rows, cols, channels) -> channels (copied once).
Image image_arg(const py::handle& obj, const std::string& what);
// True when obj is an array the library can use without a copy (see above).
bool is_library_buffer(const py::handle& obj);

// What a poll of Python decided: go on, stop because the progress callback returned False,
// stop because of Ctrl-C (KeyboardInterrupt), or stop because of another Python exception.
enum class Poll { kContinue, kStopRequested, kKeyboardInterrupt, kError };

// Runs work() on a worker thread with the GIL released. The calling thread wakes every poll_s
// seconds: it runs the signal handlers (PyErr_CheckSignals, so Ctrl-C raises KeyboardInterrupt
// in Python code) and calls progress(info(seconds)) when given (info: the elapsed seconds as a
// float when not given; built with the GIL held). Anything but kContinue raises `stop`
// (the library ends cleanly and keeps what it has); the first such decision is returned. A
// Python exception other than KeyboardInterrupt is re-raised once the work has ended.
// Exceptions of work() are re-thrown on the calling thread.
Poll run_with_interrupt(const std::function<void()>& work, std::atomic<bool>& stop,
                        const py::object& progress, double poll_s,
                        const std::function<py::object(double)>& info = {});

// Called from a library progress hook on the calling thread (GIL not held): acquires the GIL,
// checks signals and calls progress(info()) when given (info is built with the GIL held).
// Other exceptions are stored in *error (kError).
Poll poll_python(const py::object& progress, const std::function<py::object()>& info,
                 std::exception_ptr* error);

// Raises KeyboardInterrupt in Python: for a Ctrl-C that stopped nothing the library could keep
// (a closed-form decode, a run that had already finished).
[[noreturn]] void raise_keyboard_interrupt();

void bind_errors(py::module_& m);
void bind_arrays(py::module_& m);
void bind_design(py::module_& m);
void bind_mask(py::module_& m);
void bind_psf(py::module_& m);
void bind_simulate(py::module_& m);
void bind_decode(py::module_& m);
void bind_metrics(py::module_& m);
void bind_search(py::module_& m);
void bind_compare(py::module_& m);
void bind_export(py::module_& m);
void bind_check(py::module_& m);
void bind_calibrate(py::module_& m);

}  // namespace pinmask::python
