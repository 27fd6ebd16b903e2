// The few collectives pinmask spreads work with, as an interface so the libraries that
// use them (island search, sweeps, batch decode) need no MPI: optimize/search/mpi/ implements it
// over MPI (pinmask_mpi, linked by the pinmask executable only), LocalComm here is the
// single-process case (rank 0 of 1) that every plain run and the Python module use.
//
// Every call is collective over all ranks unless said otherwise, made from one thread per rank.
// Messages are byte buffers; callers encode their own values (optimize/search/byte_codec.hpp).
// Errors are exceptions (RuntimeFailure); nothing prints or exits.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

namespace pinmask {

using Bytes = std::vector<std::uint8_t>;

class RankComm {
  public:
    static constexpr int kAnySource = -1;
    static constexpr int kAnyTag = -1;
    struct Message {
        int source = 0;
        int tag = 0;
        Bytes bytes;
    };

    virtual ~RankComm() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;

    // Root's buffer replaces every other rank's buffer.
    virtual void broadcast(Bytes& bytes, int root) = 0;
    // Sends `mine` to rank + 1 and returns what rank - 1 sent (ring, modulo size). On one rank:
    // a copy of `mine`.
    virtual Bytes ring_shift(const Bytes& mine) = 0;
    // Every rank's buffer, in rank order, on `root`; other ranks get an empty vector.
    virtual std::vector<Bytes> gather(const Bytes& mine, int root) = 0;
    // Sum and logical or over all ranks, on every rank.
    virtual std::int64_t sum(std::int64_t value) = 0;
    virtual bool any(bool value) = 0;
    virtual void barrier() = 0;

    // Point to point (not collective), for master/worker queues: tag >= 0. On one rank, a
    // message sent to rank 0 is queued in memory and received in order.
    virtual void send(const Bytes& bytes, int dest, int tag) = 0;
    // Blocks until a message from `source` (or kAnySource) with `tag` (or kAnyTag) arrives.
    virtual Message receive(int source = kAnySource, int tag = kAnyTag) = 0;
};

// One process: rank 0 of 1. Collectives are identities; send/receive go through a queue.
class LocalComm : public RankComm {
  public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    void broadcast(Bytes&, int root) override;
    Bytes ring_shift(const Bytes& mine) override { return mine; }
    std::vector<Bytes> gather(const Bytes& mine, int root) override;
    std::int64_t sum(std::int64_t value) override { return value; }
    bool any(bool value) override { return value; }
    void barrier() override {}
    void send(const Bytes& bytes, int dest, int tag) override;
    Message receive(int source = kAnySource, int tag = kAnyTag) override;

  private:
    std::deque<Message> queue_;
};

}  // namespace pinmask
