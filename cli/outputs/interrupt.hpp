// SIGINT/SIGTERM as a flag: long runs (search, decode) poll it, stop cleanly and write the best
// result so far. Every signal only sets the flag (and counts): the first always ends with the
// best so far written, later ones cannot lose it (coreutils `timeout` sends SIGTERM to the
// process and again to its group; a second Ctrl-C used to kill before the write). A run that
// must die at once can still be killed with SIGKILL.
#pragma once

#include <atomic>

namespace pinmask::cli {

// Installs the handlers (idempotent) and returns the flag they set.
const std::atomic<bool>& install_interrupt_flag();

// Signals received since the handlers were installed.
int interrupt_count();

// For the commands that do not poll the flag (export, psf, check, ...): SIGINT, SIGTERM, SIGHUP
// and SIGQUIT unlink this process's pending temporary files (core/files/atomic_file) and then end
// it as the signal would have, so an interrupted run leaves neither a final file nor a *.tmp-*
// file. install_interrupt_flag() later replaces the SIGINT/SIGTERM handlers for a command that
// stops cleanly instead. cli/main.cpp installs this first.
void install_cleanup_on_signal();

}  // namespace pinmask::cli
