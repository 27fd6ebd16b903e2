#include "cli/outputs/interrupt.hpp"

#include <csignal>

#include "core/files/atomic_file.hpp"

namespace pinmask::cli {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_count{0};

extern "C" void on_signal(int) {
    g_interrupted.store(true);
    g_count.fetch_add(1);
}

extern "C" void on_fatal_signal(int sig) {
    remove_pending_temporaries();
    ::signal(sig, SIG_DFL);  // then die of the same signal (the shell sees 128 + sig)
    ::raise(sig);
}

}  // namespace

void install_cleanup_on_signal() {
    struct sigaction sa {};
    sa.sa_handler = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        struct sigaction old {};
        sigaction(sig, nullptr, &old);
        // A signal the parent set to be ignored (nohup: SIGHUP) stays ignored.
        if (old.sa_handler != SIG_IGN) sigaction(sig, &sa, nullptr);
    }
}

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
