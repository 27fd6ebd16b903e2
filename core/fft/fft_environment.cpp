#include "core/fft/fft_environment.hpp"

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "core/fft/fft.hpp"

namespace pinmask {

WisdomChoice wisdom_choice_from_environment() {
    if (const char* w = std::getenv("PINMASK_WISDOM")) {
        const std::string v = w;
        if (v.empty() || v == "off" || v == "none" || v == "0") return {"", "disabled"};
        return {v, "PINMASK_WISDOM"};
    }
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) {
        return {std::string(x) + "/pinmask/wisdom", "XDG_CACHE_HOME"};
    }
    if (const char* h = std::getenv("HOME"); h && *h) {
        return {std::string(h) + "/.cache/pinmask/wisdom", "HOME"};
    }
    return {"", "disabled"};
}

int default_thread_count() {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : static_cast<int>(std::min(n, 64u));
}

std::vector<std::string> configure_fft_from_environment() {
    const WisdomChoice w = wisdom_choice_from_environment();
    set_fft_planner(w.path.empty() ? FftPlanner::kEstimate : FftPlanner::kMeasure);
    set_fft_threads(default_thread_count());
    return set_fft_wisdom_file(w.path);
}

}  // namespace pinmask
