// The MPI collectives (optimize/search/mpi/mpi_comm) checked against what each rank can compute on
// its own: run by CTest under `mpirun -n 3` (test "mpi") and as a plain process (test "mpi-plain",
// where world_comm() is the single-rank LocalComm). Every rank runs the same cases in the same
// order (CHECK, never REQUIRE, so no rank skips a collective).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "optimize/search/byte_codec.hpp"
#include "optimize/search/mpi/mpi_comm.hpp"

using namespace pinmask;

namespace {
// A buffer only rank r makes: r + 1 bytes, values from r.
Bytes rank_bytes(int r) {
    Bytes b(static_cast<std::size_t>(r + 1));
    std::iota(b.begin(), b.end(), static_cast<std::uint8_t>(10 * r));
    return b;
}
}  // namespace

TEST_CASE("world_comm: MPI exactly when launched by mpirun") {
    RankComm& w = world_comm();
    CHECK(mpi_active() == launched_by_mpi());
    CHECK(w.size() >= 1);
    CHECK(w.rank() >= 0);
    CHECK(w.rank() < w.size());
    CHECK(&w == &world_comm());
}

TEST_CASE("broadcast: the root's bytes everywhere, any length") {
    RankComm& w = world_comm();
    const int root = w.size() - 1;
    Bytes b = w.rank() == root ? Bytes{1, 2, 3, 4, 5} : Bytes{9};
    w.broadcast(b, root);
    CHECK(b == Bytes{1, 2, 3, 4, 5});
    Bytes empty = w.rank() == 0 ? Bytes{} : Bytes{7, 7};
    w.broadcast(empty, 0);
    CHECK(empty.empty());
}

TEST_CASE("ring_shift: each rank gets its left neighbour's buffer") {
    RankComm& w = world_comm();
    const int prev = (w.rank() + w.size() - 1) % w.size();
    CHECK(w.ring_shift(rank_bytes(w.rank())) == rank_bytes(prev));
}

TEST_CASE("gather: every buffer in rank order on the root only") {
    RankComm& w = world_comm();
    for (int root : {0, w.size() - 1}) {
        const std::vector<Bytes> all = w.gather(rank_bytes(w.rank()), root);
        if (w.rank() == root) {
            REQUIRE(all.size() == static_cast<std::size_t>(w.size()));
            for (int r = 0; r < w.size(); ++r)
                CHECK(all[static_cast<std::size_t>(r)] == rank_bytes(r));
        } else {
            CHECK(all.empty());
        }
    }
}

TEST_CASE("sum and any over ranks") {
    RankComm& w = world_comm();
    const std::int64_t n = w.size();
    CHECK(w.sum(w.rank() + 1) == n * (n + 1) / 2);
    CHECK(w.sum(std::int64_t{1} << 40) == n << 40);  // 64-bit, no int overflow
    CHECK(w.any(w.rank() == w.size() - 1));
    CHECK_FALSE(w.any(false));
    w.barrier();
}

TEST_CASE("send/receive: a master/worker round trip with tags") {
    RankComm& w = world_comm();
    // Every rank (rank 0 included) sends its buffer to rank 0 with tag 3 + rank; rank 0
    // answers each with the buffer reversed under tag 1.
    w.send(rank_bytes(w.rank()), 0, 3 + w.rank());
    if (w.rank() == 0) {
        std::vector<int> seen(static_cast<std::size_t>(w.size()), 0);
        // Rank 0's own reply (tag 1) may already be queued: receive each rank's request by
        // its own tag, never "any tag", so the reply is left for the receive below.
        for (int i = 0; i < w.size(); ++i) {
            RankComm::Message m = w.receive(RankComm::kAnySource, 3 + i);
            CHECK(m.tag == 3 + m.source);
            CHECK(m.bytes == rank_bytes(m.source));
            ++seen[static_cast<std::size_t>(m.source)];
            Bytes back(m.bytes.rbegin(), m.bytes.rend());
            w.send(back, m.source, 1);
        }
        for (int s : seen) CHECK(s == 1);
    }
    const RankComm::Message reply = w.receive(0, 1);
    Bytes expect = rank_bytes(w.rank());
    std::reverse(expect.begin(), expect.end());
    CHECK(reply.source == 0);
    CHECK(reply.bytes == expect);
    CHECK_THROWS(w.send(Bytes{}, 0, -1));
}

TEST_CASE("byte codec round trip through a ring shift, infinities and NaN exact") {
    RankComm& w = world_comm();
    ByteWriter out;
    out.i64(-5 - w.rank());
    out.f64(INFINITY);
    out.f64(0.1 * w.rank());
    out.str("rank " + std::to_string(w.rank()));
    const Bytes in = w.ring_shift(out.bytes());
    const int prev = (w.rank() + w.size() - 1) % w.size();
    ByteReader r(in);
    CHECK(r.i64() == -5 - prev);
    CHECK(r.f64() == INFINITY);
    CHECK(r.f64() == 0.1 * prev);
    CHECK(r.str() == "rank " + std::to_string(prev));
    CHECK(r.done());
    Bytes cut = in;
    cut.resize(cut.size() - 1);
    ByteReader bad(cut);
    bad.i64();
    bad.f64();
    bad.f64();
    CHECK_THROWS(bad.str());  // truncated
}
