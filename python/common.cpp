#include "python/common.hpp"

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

#include "core/errors/error.hpp"
#include "core/files/path_text.hpp"
#include "core/limits/resource_limits.hpp"
#include "python/keyword_names.hpp"

namespace pinmask::python {

namespace {

std::atomic<long long> g_input_copies{0};  // input arrays copied into library planes

void delete_plane(PyObject* capsule) {
    delete static_cast<Plane*>(PyCapsule_GetPointer(capsule, kPlaneCapsule));
}

// The Plane behind obj when obj is a whole module-made float64 array, else null.
const Plane* library_plane(const py::handle& obj) {
    if (!py::isinstance<py::array>(obj)) return nullptr;
    const auto arr = py::reinterpret_borrow<py::array>(obj);
    const py::handle base = arr.base();
    if (!base || !PyCapsule_CheckExact(base.ptr())) return nullptr;
    const char* name = PyCapsule_GetName(base.ptr());
    if (name == nullptr || std::strcmp(name, kPlaneCapsule) != 0) return nullptr;
    const auto* plane = static_cast<const Plane*>(PyCapsule_GetPointer(base.ptr(), kPlaneCapsule));
    if (plane == nullptr) {
        PyErr_Clear();
        return nullptr;
    }
    if (arr.ndim() != 2 || !arr.dtype().is(py::dtype::of<double>()) ||
        arr.data() != static_cast<const void*>(plane->data()) || arr.shape(0) != plane->rows() ||
        arr.shape(1) != plane->cols() ||
        (plane->size() > 1 &&
         (arr.strides(0) != static_cast<py::ssize_t>(plane->cols() * 8) || arr.strides(1) != 8))) {
        return nullptr;
    }
    return plane;
}

template <class T>
void copy_2d(const py::array_t<T>& a, Plane& out) {
    const auto v = a.template unchecked<2>();
    out.resize(v.shape(0), v.shape(1));
    for (py::ssize_t r = 0; r < v.shape(0); ++r)
        for (py::ssize_t c = 0; c < v.shape(1); ++c) out(r, c) = static_cast<double>(v(r, c));
}

// obj as a float32 or float64 array without conversion when it already is one.
py::array as_float_array(const py::handle& obj, const std::string& what) {
    py::array arr = py::array::ensure(obj);
    if (!arr) {
        PyErr_Clear();
        throw invalid_field(what, py::str(py::type::of(obj)).cast<std::string>(),
                            "must be a numpy array (or array-like) of numbers");
    }
    // Charged from its shape before anything is copied (a view of 200000 x 200000 owns no
    // memory, but its float64 copy would): the process's memory budget refuses it here.
    double elements = 1.0;
    for (py::ssize_t k = 0; k < arr.ndim(); ++k) elements *= static_cast<double>(arr.shape(k));
    check_memory(elements * sizeof(double), what + " (an array of " +
                                                std::to_string(static_cast<long long>(elements)) +
                                                " values as float64)");
    if (arr.dtype().is(py::dtype::of<float>()) || arr.dtype().is(py::dtype::of<double>()))
        return arr;
    const char kind = arr.dtype().kind();
    if (kind == 'c')
        throw invalid_field(what, "complex array", "must be real (float32 or float64)");
    // Numbers only: a bool mask, strings or objects are not light values (numpy would turn
    // True into 1.0 without a word).
    if (kind != 'f' && kind != 'i' && kind != 'u') {
        throw py::type_error(py_names::spell_keywords(
            what + ": an array of dtype " + py::str(arr.dtype()).cast<std::string>() +
            " is not an image: give numbers (float32 or float64; integers are converted)"));
    }
    auto conv = py::array_t<double, py::array::forcecast>::ensure(arr);
    if (!conv) {
        PyErr_Clear();
        throw invalid_field(what, py::str(arr.dtype()).cast<std::string>(),
                            "dtype cannot be converted to float64");
    }
    return conv;
}

void copy_plane(const py::array& arr, Plane& out) {
    ++g_input_copies;
    if (arr.dtype().is(py::dtype::of<float>())) {
        copy_2d(py::array_t<float>(py::reinterpret_borrow<py::array_t<float>>(arr)), out);
        return;
    }
    const auto d = py::reinterpret_borrow<py::array_t<double>>(arr);
    if (d.flags() & py::array::c_style) {  // one memcpy
        out.resize(d.shape(0), d.shape(1));
        if (out.size() > 0) std::memcpy(out.data(), d.data(), sizeof(double) * out.size());
        return;
    }
    copy_2d(d, out);
}

}  // namespace

py::array_t<double> to_array(Plane&& plane) {
    auto* owned = new Plane(std::move(plane));
    py::capsule owner(owned, kPlaneCapsule, &delete_plane);
    const py::ssize_t rows = owned->rows(), cols = owned->cols();
    return py::array_t<double>(
        {rows, cols},
        {static_cast<py::ssize_t>(sizeof(double)) * cols, static_cast<py::ssize_t>(sizeof(double))},
        owned->data(), owner);
}

py::array_t<double> to_array(const Plane& plane) { return to_array(Plane(plane)); }

py::array image_to_array(Image&& image) {
    if (image.n_channels() == 1) return to_array(std::move(image.channels[0]));
    const py::ssize_t rows = image.rows(), cols = image.cols(), ch = image.n_channels();
    py::array_t<double> out({rows, cols, ch});
    auto v = out.mutable_unchecked<3>();
    for (py::ssize_t k = 0; k < ch; ++k) {
        const Plane& p = image.channels[static_cast<std::size_t>(k)];
        for (py::ssize_t r = 0; r < rows; ++r)
            for (py::ssize_t c = 0; c < cols; ++c) v(r, c, k) = p(r, c);
    }
    return out;
}

bool is_library_buffer(const py::handle& obj) { return library_plane(obj) != nullptr; }

PlaneArg plane_arg(const py::handle& obj, const std::string& what) {
    PlaneArg a;
    if (const Plane* p = library_plane(obj)) {
        a.borrowed_ = p;
        a.keep_ = py::reinterpret_borrow<py::object>(obj);
        return a;
    }
    const py::array arr = as_float_array(obj, what);
    if (arr.ndim() != 2) {
        throw invalid_field(what, "an array of " + std::to_string(arr.ndim()) + " dimension(s)",
                            "must be 2-D (rows, cols)");
    }
    copy_plane(arr, a.owned_);
    return a;
}

Image image_arg(const py::handle& obj, const std::string& what) {
    if (library_plane(obj) != nullptr) {  // an Image owns its planes: one copy
        ++g_input_copies;
        return Image(plane_arg(obj, what).get());
    }
    const py::array arr = as_float_array(obj, what);
    if (arr.ndim() == 2) {
        Image img;
        img.channels.emplace_back();
        copy_plane(arr, img.channels[0]);
        return img;
    }
    if (arr.ndim() != 3) {
        throw invalid_field(what, "an array of " + std::to_string(arr.ndim()) + " dimension(s)",
                            "must be 2-D (rows, cols) or 3-D (rows, cols, channels)");
    }
    // The channels pinmask's image files hold (core/image/image_io): grey or RGB. Another count
    // (an RGBA array, two planes) was decoded channel by channel where the command refuses it.
    if (arr.shape(2) != 1 && arr.shape(2) != 3) {
        throw invalid_field(what, "an array of " + std::to_string(arr.shape(2)) + " channels",
                            "must have 1 (grey) or 3 (RGB) channels, as the image files pinmask "
                            "reads (drop an alpha channel first: image[..., :3])");
    }
    ++g_input_copies;
    const auto d = py::array_t<double, py::array::forcecast>::ensure(arr);
    const auto v = d.unchecked<3>();
    Image img(static_cast<int>(v.shape(0)), static_cast<int>(v.shape(1)),
              static_cast<int>(v.shape(2)));
    for (py::ssize_t k = 0; k < v.shape(2); ++k) {
        Plane& p = img.channels[static_cast<std::size_t>(k)];
        for (py::ssize_t r = 0; r < v.shape(0); ++r)
            for (py::ssize_t c = 0; c < v.shape(1); ++c) p(r, c) = v(r, c, k);
    }
    return img;
}

Poll run_with_interrupt(const std::function<void()>& work, std::atomic<bool>& stop,
                        const py::object& progress, double poll_s,
                        const std::function<py::object(double)>& info) {
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
    std::exception_ptr work_error;
    std::exception_ptr py_error;
    Poll decision = Poll::kContinue;
    const auto t0 = std::chrono::steady_clock::now();
    std::thread worker;
    {
        py::gil_scoped_release release;
        worker = std::thread([&] {
            try {
                work();
            } catch (...) {
                work_error = std::current_exception();
            }
            std::lock_guard<std::mutex> lock(mu);
            done = true;
            cv.notify_all();
        });
    }
    const auto wait = std::chrono::duration<double>(poll_s > 0 ? poll_s : 0.05);
    for (;;) {
        {
            py::gil_scoped_release release;
            std::unique_lock<std::mutex> lock(mu);
            cv.wait_for(lock, wait, [&] { return done; });
            if (done) break;
        }
        if (decision != Poll::kContinue) continue;  // stopping: wait for the work to end
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        decision = poll_python(
            progress, [&] { return info ? info(seconds) : py::object(py::float_(seconds)); },
            &py_error);
        if (decision != Poll::kContinue) stop.store(true);
    }
    {
        py::gil_scoped_release release;
        worker.join();
    }
    if (work_error) std::rethrow_exception(work_error);
    if (py_error) std::rethrow_exception(py_error);
    return decision;
}

Poll poll_python(const py::object& progress, const std::function<py::object()>& info,
                 std::exception_ptr* error) {
    py::gil_scoped_acquire gil;
    try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!progress.is_none()) {
            const py::object r = progress(info());
            if (!r.is_none() && !r.cast<bool>()) return Poll::kStopRequested;
        }
        return Poll::kContinue;
    } catch (py::error_already_set& e) {
        if (e.matches(PyExc_KeyboardInterrupt)) return Poll::kKeyboardInterrupt;
        *error = std::current_exception();
        return Poll::kError;
    } catch (...) {
        *error = std::current_exception();
        return Poll::kError;
    }
}

void refuse_path_with_nul(const std::string& text) {
    std::string shown;  // the NUL as \x00: a C string would end the message there
    for (const char c : printable_text(text))
        shown += c == '\0' ? std::string("\\x00") : std::string(1, c);
    throw InvalidInput("path '" + shown +
                       "': the name holds a NUL byte (\\u0000), which no file name can");
}

void raise_keyboard_interrupt() {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
}

namespace {

// "Unable to cast Python instance of type <class 'str'> to C++ type 'double'" (or the short
// form of a release build) -> "a value of type str was given where a number is expected".
std::string cast_error_words(const std::string& what) {
    std::string given = "another type";
    if (const auto at = what.find("<class '"); at != std::string::npos) {
        const auto end = what.find('\'', at + 8);
        if (end != std::string::npos) given = "type " + what.substr(at + 8, end - at - 8);
    }
    std::string wanted = "a value of another type";
    const auto cpp = what.find("C++ type '");
    const std::string type = cpp == std::string::npos
                                 ? std::string()
                                 : what.substr(cpp + 10, what.find('\'', cpp + 10) - cpp - 10);
    if (type == "double" || type == "float") wanted = "a number";
    if (type == "int" || type == "long" || type.find("int64") != std::string::npos ||
        type.find("uint") != std::string::npos)
        wanted = "an integer";
    if (type.find("string") != std::string::npos) wanted = "a string";
    if (type == "bool") wanted = "True or False";
    return "a value of " + given + " was given where " + wanted +
           " is expected (see the function's help for each keyword's type)";
}

}  // namespace

void bind_errors(py::module_& m) {
    (void)m;
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const py::error_already_set&) {
            throw;
        } catch (const py::cast_error& e) {
            // A value of the wrong type met a conversion inside a call: said as a TypeError in
            // the module's words, not pybind11's "Unable to cast ... to C++ type ...".
            PyErr_SetString(PyExc_TypeError, cast_error_words(e.what()).c_str());
        } catch (const py::builtin_exception&) {
            throw;
        } catch (const std::bad_alloc&) {
            throw;
        } catch (const InvalidInput& e) {  // ResourceLimit too: the request is at fault
            PyErr_SetString(PyExc_ValueError, py_names::spell_keywords(e.what()).c_str());
        } catch (const std::exception& e) {
            PyErr_SetString(PyExc_RuntimeError, py_names::spell_keywords(e.what()).c_str());
        }
    });
}

void bind_arrays(py::module_& m) {
    m.def(
        "is_library_buffer", [](const py::handle& a) { return is_library_buffer(a); },
        py::arg("array"),
        "True when `array` is one the module returned (float64, C order, its whole buffer): "
        "decode() uses such a capture or PSF in place. Any other float32 or float64 input is "
        "copied once; other dtypes are converted first.");
    m.def(
        "input_copies", [] { return g_input_copies.load(); },
        "How many input arrays the module has copied into library planes since it was loaded "
        "(a diagnostic of the zero-copy contract).");
}

}  // namespace pinmask::python
