#include "cli/outputs/decode_progress.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <optional>
#include <string>

#include "cli/outputs/progress.hpp"
#include "core/units/number_format.hpp"

namespace pinmask::cli {

namespace {

// A decode shorter than this prints no progress.
constexpr double kQuietSeconds = 2.0;
// How often the reporting thread looks at the count (a finished decode wakes it at once).
constexpr std::chrono::milliseconds kPoll{100};

}  // namespace

void run_with_decode_progress(long long total, bool show, const std::atomic<long long>& done,
                              const std::function<void()>& work) {
    if (!show || total <= 0) {
        work();
        return;
    }
    using Clock = std::chrono::steady_clock;
    const Clock::time_point t0 = Clock::now();
    std::future<void> running = std::async(std::launch::async, work);
    std::optional<ProgressLine> bar;
    const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    while (running.wait_for(kPoll) != std::future_status::ready) {
        const double t = seconds();
        if (t < kQuietSeconds) continue;
        if (!bar) bar.emplace("pinmask decode");
        const long long d = std::min(done.load(std::memory_order_relaxed), total);
        std::string text =
            d == 0 ? "preparing (FFT plans, first iteration), " + format_number(t, 3) + " s"
                   : "iteration " + std::to_string(d) + " of at most " + std::to_string(total) +
                         ", " + format_number(t, 3) + " s";
        if (d > 0)
            text += ", at most " + format_number(t * double(total - d) / double(d), 3) + " s left";
        bar->update(std::min(0.99, double(d) / double(total)), text);
    }
    if (bar) {
        bar->update(1.0, std::to_string(done.load()) + " iterations in " +
                             format_number(seconds(), 3) + " s");
        bar->finish();
    }
    running.get();  // rethrows what work() threw
}

}  // namespace pinmask::cli
