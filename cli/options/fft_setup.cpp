#include "cli/options/fft_setup.hpp"

#include <iostream>
#include <set>
#include <string>
#include <utility>

#include "core/fft/fft.hpp"
#include "core/fft/planning_notice.hpp"

namespace pinmask::cli {

void configure_fft_for_process() {
    for (const std::string& warning : configure_fft_from_environment())
        std::cerr << "pinmask: warning: " << warning << "\n";
    // One line per size measured (its forward, inverse and single-precision plans follow it).
    // The notice runs under the planner's lock: the wisdom path is read here, not inside it.
    const std::string wisdom = fft_wisdom_file();
    const std::string kept = wisdom.empty() ? std::string("; PINMASK_WISDOM=off: not kept")
                                            : "; kept in " + wisdom + " for later runs";
    set_fft_planning_notice(
        [said = std::set<std::pair<int, int>>(), kept](int rows, int cols) mutable {
            if (!said.insert({rows, cols}).second) return;
            std::cerr << "pinmask: planning FFTs for " << rows << " x " << cols
                      << " once (FFTW_MEASURE, up to " << kFftPlanTimeLimitSeconds << " s a plan)"
                      << kept << "\n";
        });
}

void print_fft_warnings() {
    for (const std::string& warning : take_fft_warnings())
        std::cerr << "pinmask: warning: " << warning << "\n";
}

}  // namespace pinmask::cli
