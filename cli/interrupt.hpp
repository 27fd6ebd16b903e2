// SIGINT/SIGTERM as a flag: long runs (search) poll it, stop cleanly and write the best result so
// far. A second signal restores the default action (so a second Ctrl-C kills at once).
#pragma once

#include <atomic>

namespace pinmask::cli {

// Installs the handlers (idempotent) and returns the flag they set.
const std::atomic<bool>& install_interrupt_flag();

}  // namespace pinmask::cli
