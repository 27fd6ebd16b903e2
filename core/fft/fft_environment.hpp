// The process's FFT set-up from its environment, shared by the executables (the pinmask command
// and the Python module) so both plan alike: FFTW_MEASURE plans remembered in a wisdom file.
//
// Wisdom file: $PINMASK_WISDOM when set (a path; "off", "none", "0" or empty disable wisdom),
// else $XDG_CACHE_HOME/pinmask/wisdom, else $HOME/.cache/pinmask/wisdom. With a wisdom file,
// plans are measured once (FFTW_MEASURE) and the choice recorded, so every later run rebuilds the
// same plans (same rounding: byte-identical outputs from run to run, core/fft/fft.hpp). Without
// one, plans are FFTW_ESTIMATE: no timing, the same plan in every run. A corrupt or foreign file is
// ignored with a warning and replaced. The libraries never call this (their default is
// kEstimate without wisdom); an executable calls it once at start.
#pragma once

#include <string>
#include <vector>

namespace pinmask {

// The wisdom path the environment selects ("" when disabled), and why.
struct WisdomChoice {
    std::string path;
    std::string source;  // "PINMASK_WISDOM", "XDG_CACHE_HOME", "HOME", or "disabled"
};
WisdomChoice wisdom_choice_from_environment();

// Hardware threads (>= 1, at most 64).
int default_thread_count();

// Sets core/fft/fft's planner (kMeasure with a wisdom file, else kEstimate), its wisdom file and
// its threads (default_thread_count()). Returns the wisdom file's warnings for the caller to show.
std::vector<std::string> configure_fft_from_environment();

}  // namespace pinmask
