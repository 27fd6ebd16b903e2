// `pinmask check --json` from the check transaction's report (io/check_files): the verdict, the
// input, the rules and where they came from, what was measured, the counts and listed
// violations, and the comparison with the design, the film's identity or the picture's
// comparison when there is one. The command prints it; Python's check() returns it as a dict.
#pragma once

#include <nlohmann/json.hpp>

#include "io/check_files.hpp"

namespace pinmask::io {

nlohmann::ordered_json check_json(const CheckReport& report);

}  // namespace pinmask::io
