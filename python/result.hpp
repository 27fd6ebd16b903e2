// Results of the module's functions: a dict whose keys also read as attributes
// (r.image is r["image"]), as scipy.optimize.OptimizeResult reads, so an editor completes them and
// a mistyped name is an AttributeError naming the keys. to_dict() gives plain dicts and lists all
// the way down.
#pragma once

#include "python/common.hpp"

namespace pinmask::python {

// Defines pinmask.Result; called once, before any binding that returns one.
void bind_result(py::module_& m);

// The dict as a Result, nested dicts (also inside lists) as Results too. Still a dict to every
// caller (Result subclasses dict), so bindings keep their py::dict types.
py::dict as_result(const py::dict& d);
// Each dict of the list as a Result (functions that return one row per item).
py::list as_result(const py::list& rows);

}  // namespace pinmask::python
