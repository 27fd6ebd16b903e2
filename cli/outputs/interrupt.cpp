#include "cli/outputs/interrupt.hpp"

#include <csignal>

namespace pinmask::cli {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_count{0};

extern "C" void on_signal(int) {
    g_interrupted.store(true);
    g_count.fetch_add(1);
}

}  // namespace

const std::atomic<bool>& install_interrupt_flag() {
    static const bool installed = [] {
        struct sigaction sa {};
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;  // the handler stays installed for later signals
        sigaction(SIGINT, &sa, nullptr);
        sigaction(SIGTERM, &sa, nullptr);
        return true;
    }();
    (void)installed;
    return g_interrupted;
}

int interrupt_count() { return g_count.load(); }

}  // namespace pinmask::cli
