// Rendering of `pinmask check` results as text (its --json is io/check_json's).
#pragma once

#include "io/check_files.hpp"

namespace pinmask::cli {

void print_check_text(const io::CheckReport& r);

}  // namespace pinmask::cli
