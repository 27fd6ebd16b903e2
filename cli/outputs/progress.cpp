#include "cli/outputs/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace pinmask::cli {

ProgressLine::ProgressLine(std::string label, double plain_interval_s)
    : label_(std::move(label)),
      interval_s_(plain_interval_s),
      terminal_(::isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::phase(const std::string& name) {
    if (terminal_) {
        std::fprintf(stderr, "\r%s...\x1b[K", name.c_str());
        std::fflush(stderr);
        drawn_ = true;
        return;
    }
    std::fprintf(stderr, "%s: %s...\n", label_.c_str(), name.c_str());
    std::fflush(stderr);
    last_plain_ = Clock::now();
    print_next_ = true;  // the work's first figures follow the phase's name at once
    plain_done_ = false;
}

void ProgressLine::update(double fraction, const std::string& text, const std::string& stage) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (stage != stage_) {
        stage_ = stage;
        print_next_ = true;
        plain_done_ = false;
    }
    if (!terminal_) {
        const Clock::time_point now = Clock::now();
        const bool done = fraction >= 1.0;
        const bool due =
            print_next_ || std::chrono::duration<double>(now - last_plain_).count() >= interval_s_;
        if ((done && !plain_done_) || (!done && due)) {
            std::fprintf(stderr, "%s: %3.0f%% %s\n", label_.c_str(), 100.0 * fraction,
                         text.c_str());
            std::fflush(stderr);
            last_plain_ = now;
            print_next_ = false;
            plain_done_ = done;
        }
        return;
    }
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth + 0.5);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r[%s] %3.0f%% %s\x1b[K", bar.c_str(), 100.0 * fraction, text.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressLine::finish() {
    if (terminal_ && drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
}

}  // namespace pinmask::cli
