#include "optimize/search/mpi/mpi_comm.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <string>
#include <thread>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

void check(int rc, const char* what) {
    if (rc == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(rc, text, &len);
    throw RuntimeFailure(std::string("MPI ") + what + " failed: " + std::string(text, len));
}

int as_count(std::size_t n, const char* what) {
    if (n > static_cast<std::size_t>(INT_MAX)) {
        throw RuntimeFailure(std::string("MPI ") + what + ": message of " + std::to_string(n) +
                             " bytes exceeds 2^31 - 1");
    }
    return static_cast<int>(n);
}

// Tags above this are the collectives' own (ring_shift); send/receive use 0 .. kMaxUserTag.
constexpr int kRingTag = 32000;

class MpiComm : public RankComm {
  public:
    MpiComm() {
        int initialized = 0;
        MPI_Initialized(&initialized);
        if (!initialized) {
            int provided = 0;
            check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided),
                  "MPI_Init_thread");
            owner_ = true;
        }
        // Errors come back as codes (then exceptions) instead of aborting the job inside MPI.
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
        check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
    }
    ~MpiComm() override {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (owner_ && !finalized) MPI_Finalize();
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }

    void broadcast(Bytes& bytes, int root) override {
        unsigned long long n = bytes.size();
        check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
        bytes.resize(static_cast<std::size_t>(n));
        check(MPI_Bcast(bytes.data(), as_count(bytes.size(), "broadcast"), MPI_BYTE, root,
                        MPI_COMM_WORLD),
              "MPI_Bcast");
    }

    Bytes ring_shift(const Bytes& mine) override {
        const int next = (rank_ + 1) % size_, prev = (rank_ + size_ - 1) % size_;
        unsigned long long n_out = mine.size(), n_in = 0;
        check(
            MPI_Sendrecv(&n_out, 1, MPI_UNSIGNED_LONG_LONG, next, kRingTag, &n_in, 1,
                         MPI_UNSIGNED_LONG_LONG, prev, kRingTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "MPI_Sendrecv");
        Bytes in(static_cast<std::size_t>(n_in));
        check(MPI_Sendrecv(mine.data(), as_count(mine.size(), "ring_shift"), MPI_BYTE, next,
                           kRingTag + 1, in.data(), as_count(in.size(), "ring_shift"), MPI_BYTE,
                           prev, kRingTag + 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Sendrecv");
        return in;
    }

    std::vector<Bytes> gather(const Bytes& mine, int root) override {
        const int n = as_count(mine.size(), "gather");
        std::vector<int> counts(rank_ == root ? static_cast<std::size_t>(size_) : 0);
        check(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, MPI_COMM_WORLD),
              "MPI_Gather");
        std::vector<int> displs;
        Bytes all;
        if (rank_ == root) {
            long long total = 0;
            for (const int c : counts) {
                displs.push_back(as_count(static_cast<std::size_t>(total), "gather"));
                total += c;
            }
            all.resize(static_cast<std::size_t>(total));
        }
        check(MPI_Gatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(),
                          MPI_BYTE, root, MPI_COMM_WORLD),
              "MPI_Gatherv");
        std::vector<Bytes> out;
        if (rank_ != root) return out;
        for (int r = 0; r < size_; ++r) {
            const auto b = all.begin() + displs[static_cast<std::size_t>(r)];
            out.emplace_back(b, b + counts[static_cast<std::size_t>(r)]);
        }
        return out;
    }

    std::int64_t sum(std::int64_t value) override {
        long long in = value, out = 0;
        check(MPI_Allreduce(&in, &out, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
        return out;
    }
    bool any(bool value) override {
        int in = value ? 1 : 0, out = 0;
        check(MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD), "MPI_Allreduce");
        return out != 0;
    }
    void barrier() override { check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

    void send(const Bytes& bytes, int dest, int tag) override {
        if (tag < 0 || tag >= kRingTag) {
            throw RuntimeFailure("MPI send: tag " + std::to_string(tag) + " must be in 0.." +
                                 std::to_string(kRingTag - 1));
        }
        check(MPI_Send(bytes.data(), as_count(bytes.size(), "send"), MPI_BYTE, dest, tag,
                       MPI_COMM_WORLD),
              "MPI_Send");
    }
    Message receive(int source, int tag) override {
        // Polls with a growing sleep (50 us .. 2 ms) instead of a blocking MPI_Probe: Open MPI
        // busy-waits inside a blocking probe, which takes a core from the threads that do the
        // work beside a waiting rank (the sweep's rank 0 runs points while it serves the queue).
        MPI_Status st;
        const int src = source == kAnySource ? MPI_ANY_SOURCE : source;
        const int tg = tag == kAnyTag ? MPI_ANY_TAG : tag;
        for (auto pause = std::chrono::microseconds(50);;) {
            int ready = 0;
            check(MPI_Iprobe(src, tg, MPI_COMM_WORLD, &ready, &st), "MPI_Iprobe");
            if (ready) break;
            std::this_thread::sleep_for(pause);
            pause = std::min(pause * 2, std::chrono::microseconds(2000));
        }
        int count = 0;
        check(MPI_Get_count(&st, MPI_BYTE, &count), "MPI_Get_count");
        Message m;
        m.source = st.MPI_SOURCE;
        m.tag = st.MPI_TAG;
        m.bytes.resize(static_cast<std::size_t>(count));
        check(MPI_Recv(m.bytes.data(), count, MPI_BYTE, m.source, m.tag, MPI_COMM_WORLD,
                       MPI_STATUS_IGNORE),
              "MPI_Recv");
        return m;
    }

  private:
    int rank_ = 0, size_ = 1;
    bool owner_ = false;
};

}  // namespace

bool launched_by_mpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
        if (std::getenv(v) != nullptr) return true;
    }
    return false;
}

RankComm& world_comm() {
    static const bool use_mpi = launched_by_mpi();
    if (use_mpi) {
        static MpiComm comm;
        return comm;
    }
    static LocalComm local;
    return local;
}

bool mpi_active() {
    int initialized = 0;
    MPI_Initialized(&initialized);
    return initialized != 0;
}

void abort_job_if_distributed(int code) {
    if (!mpi_active()) return;
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (finalized) return;
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

}  // namespace pinmask
