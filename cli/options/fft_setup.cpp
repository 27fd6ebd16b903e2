#include "cli/options/fft_setup.hpp"

#include <iostream>

#include "core/fft/fft.hpp"

namespace pinmask::cli {

void configure_fft_for_process() {
    for (const std::string& warning : configure_fft_from_environment())
        std::cerr << "pinmask: warning: " << warning << "\n";
}

void print_fft_warnings() {
    for (const std::string& warning : take_fft_warnings())
        std::cerr << "pinmask: warning: " << warning << "\n";
}

}  // namespace pinmask::cli
