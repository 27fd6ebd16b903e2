#include "python/result.hpp"

#include <pybind11/eval.h>

namespace pinmask::python {

namespace {

// The class and its recursive conversion, written in Python: attribute access and repr are
// Python-level behaviour, and the class must pickle as pinmask.Result.
constexpr const char* kResultSource = R"(
class Result(dict):
    """A result of a pinmask function: a dict whose keys also read as attributes.

    r.image is r["image"]; dir(r) lists the keys; nested dicts are Results too; to_dict()
    returns plain dicts and lists all the way down.
    """

    __slots__ = ()

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                f"pinmask.Result has no key {name!r}; its keys: {', '.join(map(str, self))}"
            ) from None

    def __dir__(self):
        return sorted(set(dir(dict)) | {k for k in self if isinstance(k, str)} | {"to_dict"})

    def to_dict(self):
        def plain(v):
            if isinstance(v, dict):
                return {k: plain(x) for k, x in v.items()}
            if isinstance(v, list):
                return [plain(x) for x in v]
            return v
        return plain(self)


def _as_result(v):
    if isinstance(v, dict):
        return Result((k, _as_result(x)) for k, x in v.items())
    if isinstance(v, list):
        return [_as_result(x) for x in v]
    return v


Result.__module__ = "pinmask"
)";

// The conversion function, set by bind_result. Held by a pointer that is never freed: a static
// py::object would be released after the interpreter has finalised, at process exit.
py::object*& converter() {
    static py::object* f = nullptr;
    return f;
}

}  // namespace

void bind_result(py::module_& m) {
    py::dict scope;
    scope["__builtins__"] = py::module_::import("builtins");
    py::exec(kResultSource, scope);
    m.attr("Result") = scope["Result"];
    converter() = new py::object(scope["_as_result"]);
}

py::dict as_result(const py::dict& d) { return (*converter())(d).cast<py::dict>(); }

py::list as_result(const py::list& rows) { return (*converter())(rows).cast<py::list>(); }

}  // namespace pinmask::python
