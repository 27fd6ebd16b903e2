#include "optimize/search/chain_codec.hpp"

#include <sstream>

#include "core/errors/error.hpp"

namespace pinmask {

void encode_pattern(ByteWriter& w, const Pattern& p) {
    w.i64(p.n);
    w.i64(p.tiles_rows);
    w.i64(p.tiles_cols);
    w.f64(p.min_spacing_cells);
    w.u64(p.pinholes.size());
    for (const Cell& c : p.pinholes) {
        w.i64(c.row);
        w.i64(c.col);
    }
}

Pattern decode_pattern(ByteReader& r) {
    Pattern p;
    p.n = static_cast<int>(r.i64());
    p.tiles_rows = static_cast<int>(r.i64());
    p.tiles_cols = static_cast<int>(r.i64());
    p.min_spacing_cells = r.f64();
    p.pinholes.resize(r.count(16));
    for (Cell& c : p.pinholes) {
        c.row = static_cast<int>(r.i64());
        c.col = static_cast<int>(r.i64());
    }
    return p;
}

void encode_chain_state(ByteWriter& w, const ChainState& s) {
    std::ostringstream rng;
    rng << s.rng;
    w.str(rng.str());
    w.i64(s.evaluations);
    w.f64(s.best_objective);
    w.i64(s.next_checkpoint);
    w.u64(s.checkpoints.size());
    for (const auto& [e, best] : s.checkpoints) {
        w.i64(e);
        w.f64(best);
    }
    w.i64(s.top.capacity());
    w.u64(s.top.items().size());
    for (const auto& item : s.top.items()) {
        w.f64(item.objective);
        encode_pattern(w, item.pattern);
    }
    w.u64(s.start ? 1 : 0);
    if (s.start) encode_pattern(w, *s.start);
    w.u64(s.best_per_holes.size());  // a pinhole-count range: the best pattern per K
    for (const auto& [k, top] : s.best_per_holes) {
        w.i64(k);
        w.u64(top.items().size());
        for (const auto& item : top.items()) {
            w.f64(item.objective);
            encode_pattern(w, item.pattern);
        }
    }
}

ChainState decode_chain_state(ByteReader& r) {
    ChainState s;
    std::istringstream rng(r.str());
    rng >> s.rng;
    if (!rng) throw RuntimeFailure("corrupt message: generator state");
    s.evaluations = r.i64();
    s.best_objective = r.f64();
    s.next_checkpoint = r.i64();
    s.checkpoints.resize(r.count(16));
    for (auto& [e, best] : s.checkpoints) {
        e = r.i64();
        best = r.f64();
    }
    const std::int64_t capacity = r.i64();
    if (capacity < 1 || capacity > 1'000'000) throw RuntimeFailure("corrupt message: top size");
    s.top = TopCandidates(static_cast<int>(capacity));
    const std::size_t items = r.count(48);
    for (std::size_t i = 0; i < items; ++i) {
        const double objective = r.f64();
        s.top.offer(decode_pattern(r), objective);
    }
    if (r.u64() != 0) s.start = decode_pattern(r);
    const std::size_t counts = r.count(16);
    for (std::size_t i = 0; i < counts; ++i) {
        const std::int64_t k = r.i64();
        if (k < 1 || k > 100'000'000) throw RuntimeFailure("corrupt message: pinhole count");
        TopCandidates& top = s.best_per_holes.try_emplace(static_cast<int>(k), 1).first->second;
        const std::size_t n = r.count(48);
        if (n > 1) throw RuntimeFailure("corrupt message: best per pinhole count");
        for (std::size_t j = 0; j < n; ++j) {
            const double objective = r.f64();
            top.offer(decode_pattern(r), objective);
        }
    }
    return s;
}

Bytes encode_chain_states(const std::vector<ChainState>& states) {
    ByteWriter w;
    w.u64(states.size());
    for (const ChainState& s : states) encode_chain_state(w, s);
    return w.take();
}

std::vector<ChainState> decode_chain_states(const Bytes& bytes) {
    ByteReader r(bytes);
    std::vector<ChainState> states(r.count(64));
    for (ChainState& s : states) s = decode_chain_state(r);
    r.expect_done();
    return states;
}

}  // namespace pinmask
