// `pinmask design --json` from the design transaction's report (design/optics/design_run): the
// camera, the geometry, every OpticsReport and WorkingDistance figure under unit-suffixed keys
// (plain and "_at_u" keys at the working distance u, "_at_inf" keys for a distant object),
// "notes" (key -> why a value is null: infinite values are null), the band and the kernel psf
// would build, a solved pinhole's grid snap, the spacing rule's packing bound, psf's kernel
// warnings and where each camera value came from. The command prints it; Python's optics()
// returns it as a dict.
#pragma once

#include <nlohmann/json.hpp>

#include "design/optics/design_run.hpp"

namespace pinmask::io {

nlohmann::ordered_json design_json(const DesignReport& report);

}  // namespace pinmask::io
