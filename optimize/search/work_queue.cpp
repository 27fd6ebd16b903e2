#include "optimize/search/work_queue.hpp"

#include <atomic>
#include <mutex>
#include <thread>

#include "core/errors/error.hpp"
#include "optimize/search/byte_codec.hpp"

namespace pinmask {
namespace {

// One item's outcome as bytes: a status byte (0 ok, 1 invalid input, 2 runtime
// failure), then the result or the message.
std::string run_item(const WorkItem& work, int index) {
    std::string out(1, '\0');  // appended to, not `"x" + s` (GCC 12's false -Wrestrict)
    try {
        out += work(index);
    } catch (const InvalidInput& e) {
        out.assign(1, '\1');
        out += e.what();
    } catch (const std::exception& e) {
        out.assign(1, '\2');
        out += e.what();
    }
    return out;
}

// Collects outcomes on rank 0; the lowest failed index wins.
struct Collector {
    WorkQueueResult out;
    int done = 0, count = 0;
    WorkDone on_done;
    bool add(int index, const std::string& outcome) {  // false: the item failed
        const bool ok = !outcome.empty() && outcome[0] == '\0';
        if (index < 0 || index >= count)
            throw RuntimeFailure("work queue: item index out of range");
        if (!ok && (out.failed_index < 0 || index < out.failed_index)) {
            out.failed_index = index;
            out.failure = outcome.empty() ? "empty outcome" : outcome.substr(1);
            out.failure_invalid_input = !outcome.empty() && outcome[0] == '\1';
        }
        if (ok) out.results[index] = outcome.substr(1);
        ++done;
        if (on_done) on_done(done, count, index);
        return ok;
    }
    WorkQueueResult finish() {
        if (out.failed_index >= 0) out.results.clear();
        return std::move(out);
    }
};

Bytes index_bytes(int index) {
    ByteWriter w;
    w.i64(index);
    return w.take();
}

WorkQueueResult run_master(RankComm& comm, int count, const WorkItem& work, const WorkDone& done) {
    Collector c;
    c.count = count;
    c.on_done = done;
    c.out.results.resize(count);
    std::mutex mu;  // guards c
    std::atomic<int> next{0};
    std::atomic<bool> stop{false};
    const auto take = [&]() -> int {
        if (stop.load()) return -1;
        const int i = next.fetch_add(1);
        return i < count ? i : -1;
    };
    // Rank 0's own share: takes indices from the same counter as the workers.
    std::thread local([&] {
        for (int i = take(); i >= 0; i = take()) {
            const std::string outcome = run_item(work, i);
            std::lock_guard<std::mutex> lock(mu);
            if (!c.add(i, outcome)) stop = true;
        }
    });
    try {
        for (int active = comm.size() - 1; active > 0;) {
            RankComm::Message m = comm.receive(RankComm::kAnySource, RankComm::kAnyTag);
            if (m.tag == kWorkResultTag) {
                ByteReader r(m.bytes);
                const auto index = static_cast<int>(r.i64());
                const std::string outcome = r.str();
                r.expect_done();
                std::lock_guard<std::mutex> lock(mu);
                if (!c.add(index, outcome)) stop = true;
            } else if (m.tag != kWorkReadyTag) {
                throw RuntimeFailure("work queue: unexpected message tag " + std::to_string(m.tag));
            }
            const int assign = take();
            comm.send(index_bytes(assign), m.source, kWorkAssignTag);
            if (assign < 0) --active;
        }
    } catch (...) {
        stop = true;
        local.join();
        throw;
    }
    local.join();
    return c.finish();
}

void run_worker(RankComm& comm, const WorkItem& work) {
    comm.send({}, 0, kWorkReadyTag);
    for (;;) {
        const RankComm::Message m = comm.receive(0, kWorkAssignTag);
        ByteReader r(m.bytes);
        const auto index = static_cast<int>(r.i64());
        r.expect_done();
        if (index < 0) return;
        ByteWriter w;
        w.i64(index);
        w.str(run_item(work, index));
        comm.send(w.take(), 0, kWorkResultTag);
    }
}

}  // namespace

WorkQueueResult run_work_queue(RankComm& comm, int count, const WorkItem& work,
                               const WorkDone& done) {
    if (comm.size() > 1) {
        if (comm.rank() == 0) return run_master(comm, count, work, done);
        run_worker(comm, work);
        return {};
    }
    Collector c;
    c.count = count;
    c.on_done = done;
    c.out.results.resize(count);
    for (int i = 0; i < count; ++i)
        if (!c.add(i, run_item(work, i))) break;
    return c.finish();
}

}  // namespace pinmask
