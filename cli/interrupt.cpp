#include "cli/interrupt.hpp"

#include <csignal>

namespace pinmask::cli {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_signal(int sig) {
    g_interrupted.store(true);
    std::signal(sig, SIG_DFL);
}

}  // namespace

const std::atomic<bool>& install_interrupt_flag() {
    static const bool installed = [] {
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        return true;
    }();
    (void)installed;
    return g_interrupted;
}

}  // namespace pinmask::cli
