#include "cli/outputs/search_snapshot.hpp"

#include <chrono>
#include <iostream>
#include <utility>

#include "core/files/atomic_file.hpp"
#include "io/mask_json.hpp"

namespace pinmask::cli {

BestSoFarSnapshot::BestSoFarSnapshot(std::filesystem::path path, Mask tmpl,
                                     const std::atomic<bool>* interrupted, double period_s)
    : path_(std::move(path)),
      tmpl_(std::move(tmpl)),
      interrupted_(interrupted),
      period_s_(period_s),
      thread_([this] { loop(); }) {}

BestSoFarSnapshot::~BestSoFarSnapshot() {
    stop();
    if (finished_) return;
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    if (!made_dir_.empty() && std::filesystem::is_empty(made_dir_, ec))
        std::filesystem::remove(made_dir_, ec);
}

void BestSoFarSnapshot::offer(const Pattern& pattern, double objective) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (best_ && !(objective < best_objective_)) return;
    best_ = pattern;
    best_objective_ = objective;
    fresh_ = true;
}

void BestSoFarSnapshot::stop() {
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void BestSoFarSnapshot::finish() {
    stop();
    finished_ = true;
    std::error_code ec;
    std::filesystem::remove(path_, ec);  // absent (a short run never wrote it): nothing to do
}

void BestSoFarSnapshot::write(const Pattern& pattern, double objective) {
    Mask m = tmpl_;
    m.pattern = pattern;
    m.pattern.pinholes = sorted_pinholes(pattern);
    m.provenance.family += " (best so far)";
    m.provenance.scores = {{"search_objective", objective}};
    const std::filesystem::path dir = path_.parent_path();
    if (!dir.empty() && !std::filesystem::exists(dir)) {
        std::filesystem::create_directories(dir);  // the final outputs would make it too
        made_dir_ = dir;
    }
    write_file_atomic(path_,
                      [&](const std::filesystem::path& tmp) { io::write_mask_file(tmp, m); });
    writes_.fetch_add(1);
}

void BestSoFarSnapshot::loop() {
    using Clock = std::chrono::steady_clock;
    // Polls the interrupt flag every 10 ms: the first signal is followed by a write within
    // about that, long before the ranks have stopped, gathered and written (and before a second
    // Ctrl-C 0.1 s later makes mpirun kill them).
    constexpr auto kPoll = std::chrono::milliseconds(10);
    std::optional<Clock::time_point> last;
    bool wrote_after_signal = false;
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stopping_) {
        wake_.wait_for(lock, kPoll, [&] { return stopping_; });
        if (stopping_ || !fresh_) continue;
        const bool signalled = interrupted_ && interrupted_->load();
        const bool due = !last || Clock::now() - *last >= std::chrono::duration<double>(period_s_);
        if (!due && !(signalled && !wrote_after_signal)) continue;
        const Pattern pattern = *best_;
        const double objective = best_objective_;
        fresh_ = false;
        lock.unlock();
        try {
            write(pattern, objective);
        } catch (const std::exception& e) {
            // A snapshot that cannot be written (disk full, folder gone) must not end the
            // search (the final outputs report their own errors): said once.
            if (!warned_) std::cerr << "\npinmask search: warning: " << e.what() << "\n";
            warned_ = true;
        }
        lock.lock();
        last = Clock::now();
        wrote_after_signal = wrote_after_signal || signalled;
    }
}

std::unique_ptr<BestSoFarSnapshot> attach_best_so_far(SearchPipelineOptions& p,
                                                      const std::filesystem::path& dir,
                                                      const std::atomic<bool>* interrupted) {
    Mask tmpl = p.tmpl;
    tmpl.provenance.seed = p.search.seed;
    tmpl.provenance.generator = p.generator;
    tmpl.provenance.family = std::string("search:") +
                             (p.search.strategy == SearchStrategy::kRandom ? "random" : "anneal");
    auto snapshot =
        std::make_unique<BestSoFarSnapshot>(dir / kBestSoFarName, std::move(tmpl), interrupted);
    p.search.on_improvement = [&snap = *snapshot](const Pattern& pattern, double objective) {
        snap.offer(pattern, objective);
    };
    if (p.islands.checkpoint) {
        p.islands.checkpoint = [write = p.islands.checkpoint, &snap = *snapshot](
                                   std::int64_t segment, std::int64_t every,
                                   const std::vector<ChainState>& states) {
            write(segment, every, states);
            for (const ChainState& s : states)
                if (!s.top.items().empty())
                    snap.offer(s.top.items().front().pattern, s.top.items().front().objective);
        };
    }
    return snapshot;
}

}  // namespace pinmask::cli
