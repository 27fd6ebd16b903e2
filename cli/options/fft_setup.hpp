// FFT planning for the `pinmask` process: core/fft/fft_environment (FFTW_MEASURE plans remembered
// in a wisdom file, threads = all cores), its warnings on stderr.
#pragma once

#include "core/fft/fft_environment.hpp"

namespace pinmask::cli {

using pinmask::default_thread_count;
using pinmask::wisdom_choice_from_environment;
using pinmask::WisdomChoice;

// Configures core/fft/fft for this process (configure_fft_from_environment) and prints wisdom
// warnings to stderr. Called once by main before any command runs.
void configure_fft_for_process();

// Prints warnings core/fft/fft recorded since (failed wisdom exports) to stderr.
void print_fft_warnings();

}  // namespace pinmask::cli
