// FFT planning for the `pinmask` process: FFTW_MEASURE plans remembered in a wisdom file.
//
// Wisdom file: $PINMASK_WISDOM when set (a path; "off" disables wisdom), else
// $XDG_CACHE_HOME/pinmask/wisdom, else $HOME/.cache/pinmask/wisdom. With a wisdom file, plans
// are measured once (FFTW_MEASURE) and the choice recorded, so every later run rebuilds the same
// plans (same rounding: byte-identical outputs from run to run). Without one (PINMASK_WISDOM=off,
// or no HOME), plans are FFTW_ESTIMATE: no timing, the same plan in every run. A corrupt or
// foreign file is ignored with a warning on stderr and replaced. Threads: all cores by default.
#pragma once

#include <string>

namespace pinmask::cli {

// The wisdom path the environment selects ("" when disabled), and why.
struct WisdomChoice {
    std::string path;
    std::string source;  // "PINMASK_WISDOM", "XDG_CACHE_HOME", "HOME", or "disabled"
};
WisdomChoice wisdom_choice_from_environment();

// Configures core/fft for this process (planner, wisdom file, threads = all cores) and prints
// wisdom warnings to stderr. Called once by main before any command runs.
void configure_fft_for_process();

// Prints warnings core/fft recorded since (failed wisdom exports) to stderr.
void print_fft_warnings();

// Hardware threads (>= 1).
int default_thread_count();

}  // namespace pinmask::cli
