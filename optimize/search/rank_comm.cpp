#include "optimize/search/rank_comm.hpp"

#include <algorithm>
#include <string>

#include "core/errors/error.hpp"

namespace pinmask {

void LocalComm::broadcast(Bytes&, int root) {
    if (root != 0) throw RuntimeFailure("broadcast: root " + std::to_string(root) + " of 1 rank");
}

std::vector<Bytes> LocalComm::gather(const Bytes& mine, int root) {
    if (root != 0) throw RuntimeFailure("gather: root " + std::to_string(root) + " of 1 rank");
    return {mine};
}

void LocalComm::send(const Bytes& bytes, int dest, int tag) {
    if (dest != 0) throw RuntimeFailure("send: destination " + std::to_string(dest) + " of 1 rank");
    if (tag < 0) throw RuntimeFailure("send: tag " + std::to_string(tag) + " must be >= 0");
    queue_.push_back({0, tag, bytes});
}

RankComm::Message LocalComm::receive(int source, int tag) {
    if (source != kAnySource && source != 0) {
        throw RuntimeFailure("receive: source " + std::to_string(source) + " of 1 rank");
    }
    const auto it = std::find_if(queue_.begin(), queue_.end(),
                                 [&](const Message& m) { return tag == kAnyTag || m.tag == tag; });
    // One process cannot wait for itself: a receive with nothing queued would block forever.
    if (it == queue_.end()) throw RuntimeFailure("receive: no message queued on a single rank");
    Message m = std::move(*it);
    queue_.erase(it);
    return m;
}

}  // namespace pinmask
