// std::filesystem::path <-> Python, in place of pybind11/stl/filesystem.h: the same conversions
// (str, bytes or any os.PathLike in; pathlib.Path out; the name "os.PathLike" in signatures), but
// a path the file system cannot take is refused in the module's words. pybind11's caster turns
// down a name with a NUL byte (which would name its prefix) by failing the overload, so the user
// read "incompatible function arguments" and the signature; here it is a ValueError naming the
// path and the reason.
#pragma once

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>

namespace pinmask::python {

// The ValueError for a path argument that holds a NUL byte (`text` as the user gave it).
[[noreturn]] void refuse_path_with_nul(const std::string& text);

}  // namespace pinmask::python

namespace pybind11::detail {

template <>
struct type_caster<std::filesystem::path> {
    PYBIND11_TYPE_CASTER(std::filesystem::path, const_name("os.PathLike"));

    bool load(handle src, bool) {
        PyObject* fspath = PyOS_FSPath(src.ptr());  // str, bytes or a PathLike's __fspath__
        if (!fspath) {
            PyErr_Clear();
            return false;  // not a path: another overload, or pybind11's TypeError
        }
        object text = reinterpret_steal<object>(fspath);
        std::string bytes;
        if (PyUnicode_Check(text.ptr())) {
            Py_ssize_t n = 0;
            const char* utf8 = PyUnicode_AsUTF8AndSize(text.ptr(), &n);
            if (!utf8) throw error_already_set();
            const std::string given(utf8, static_cast<std::size_t>(n));
            if (given.find('\0') != std::string::npos) pinmask::python::refuse_path_with_nul(given);
            // The file system's encoding (surrogateescape on POSIX), as os.fsencode.
            object encoded = reinterpret_steal<object>(PyUnicode_EncodeFSDefault(text.ptr()));
            if (!encoded) throw error_already_set();
            bytes.assign(PyBytes_AsString(encoded.ptr()),
                         static_cast<std::size_t>(PyBytes_Size(encoded.ptr())));
        } else {
            bytes.assign(PyBytes_AsString(text.ptr()),
                         static_cast<std::size_t>(PyBytes_Size(text.ptr())));
            if (bytes.find('\0') != std::string::npos) pinmask::python::refuse_path_with_nul(bytes);
        }
        value = std::filesystem::path(bytes);
        return true;
    }

    static handle cast(const std::filesystem::path& p, return_value_policy, handle) {
        object str = reinterpret_steal<object>(PyUnicode_DecodeFSDefaultAndSize(
            p.native().data(), static_cast<Py_ssize_t>(p.native().size())));
        if (!str) return nullptr;
        return module_::import("pathlib").attr("Path")(str).release();
    }
};

}  // namespace pybind11::detail
