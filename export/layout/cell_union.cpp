#include "export/layout/cell_union.hpp"

#include <algorithm>
#include <deque>
#include <string>
#include <unordered_map>

#include "core/errors/error.hpp"
#include "export/layout/rings.hpp"

namespace pinmask {
namespace {

class CellUnion {
  public:
    CellUnion(const std::vector<std::uint8_t>& occ, int rows, int cols,
              const std::vector<std::int64_t>& xe, const std::vector<std::int64_t>& ye,
              std::size_t max_vertices)
        : occ_(occ), rows_(rows), cols_(cols), xe_(xe), ye_(ye), max_vertices_(max_vertices) {}

    std::vector<Ring> run() {
        mark_cuts();
        label_.assign(occ_.size(), 0);
        for (int r = 0; r < rows_; ++r)
            for (int c = 0; c < cols_; ++c) {
                const std::size_t i = index(r, c);
                if (!occ_[i] || label_[i] != 0) continue;
                const std::vector<std::size_t> cells = flood(i, 0, 0, rows_, next_id_++);
                emit(cells);
            }
        return std::move(out_);
    }

  private:
    std::size_t index(int r, int c) const { return std::size_t(r) * std::size_t(cols_) + c; }

    // Cut rows: cut_[r] forbids joining rows r - 1 and r. A cut at the top row of every hole.
    void mark_cuts() {
        cut_.assign(std::size_t(rows_) + 1, 0);
        const int pr = rows_ + 2, pc = cols_ + 2;  // padded by one empty cell on every side
        std::vector<std::uint8_t> seen(std::size_t(pr) * pc, 0);
        auto empty = [&](int r, int c) {
            if (r == 0 || c == 0 || r == pr - 1 || c == pc - 1) return true;
            return occ_[index(r - 1, c - 1)] == 0;
        };
        auto bfs = [&](int r0, int c0) {
            int top = r0;
            std::deque<std::pair<int, int>> q{{r0, c0}};
            seen[std::size_t(r0) * pc + c0] = 1;
            while (!q.empty()) {
                auto [r, c] = q.front();
                q.pop_front();
                top = std::min(top, r);
                const int dr[4] = {1, -1, 0, 0}, dc[4] = {0, 0, 1, -1};
                for (int k = 0; k < 4; ++k) {
                    const int nr = r + dr[k], nc = c + dc[k];
                    if (nr < 0 || nc < 0 || nr >= pr || nc >= pc) continue;
                    std::uint8_t& s = seen[std::size_t(nr) * pc + nc];
                    if (s || !empty(nr, nc)) continue;
                    s = 1;
                    q.push_back({nr, nc});
                }
            }
            return top;
        };
        bfs(0, 0);  // the outside
        for (int r = 1; r < pr - 1; ++r)
            for (int c = 1; c < pc - 1; ++c)
                if (!seen[std::size_t(r) * pc + c] && empty(r, c)) cut_[bfs(r, c) - 1] = 1;
    }

    // Edge-connected occupied cells reachable from `start` inside rows [r0, r1), not crossing
    // cuts, restricted to cells currently labelled `from`; they get label `id`.
    std::vector<std::size_t> flood(std::size_t start, std::uint32_t from, int r0, int r1,
                                   std::uint32_t id) {
        std::vector<std::size_t> cells{start};
        label_[start] = id;
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const int r = int(cells[k] / cols_), c = int(cells[k] % cols_);
            auto visit = [&](int nr, int nc, bool allowed) {
                if (!allowed || nr < r0 || nr >= r1 || nc < 0 || nc >= cols_) return;
                const std::size_t j = index(nr, nc);
                if (!occ_[j] || label_[j] != from) return;
                label_[j] = id;
                cells.push_back(j);
            };
            visit(r + 1, c, !cut_[r + 1]);
            visit(r - 1, c, !cut_[r]);
            visit(r, c + 1, true);
            visit(r, c - 1, true);
        }
        return cells;
    }

    void emit(const std::vector<std::size_t>& cells) {
        const std::uint32_t id = label_[cells.front()];
        if (cells.size() == 1) {
            const int r = int(cells[0] / cols_), c = int(cells[0] % cols_);
            out_.push_back(box_ring({xe_[c], ye_[r + 1], xe_[c + 1], ye_[r]}));
            return;
        }
        Ring ring = trace(cells, id);
        if (ring.size() <= max_vertices_) {
            out_.push_back(std::move(ring));
            return;
        }
        int lo = rows_, hi = -1;
        for (std::size_t i : cells) {
            lo = std::min(lo, int(i / cols_));
            hi = std::max(hi, int(i / cols_));
        }
        const int mid = (lo + hi + 1) / 2;  // lo < mid <= hi: a single row never gets here
        for (const auto& [a, b] : {std::pair{lo, mid}, std::pair{mid, hi + 1}}) {
            for (std::size_t i : cells) {
                const int r = int(i / cols_);
                if (r < a || r >= b || label_[i] != id) continue;
                emit(flood(i, id, a, b, next_id_++));
            }
        }
    }

    // The boundary of one piece, interior on the left (counter-clockwise with y up).
    Ring trace(const std::vector<std::size_t>& cells, std::uint32_t id) const {
        const std::uint64_t w = std::uint64_t(cols_) + 1;
        auto key = [w](std::uint64_t i, std::uint64_t j) { return i * w + j; };
        auto in = [&](int r, int c) {
            return r >= 0 && c >= 0 && r < rows_ && c < cols_ && label_[index(r, c)] == id;
        };
        std::unordered_map<std::uint64_t, std::uint64_t> next;
        next.reserve(cells.size() * 2);
        std::uint64_t start = 0;
        auto add = [&](std::uint64_t from, std::uint64_t to) {
            if (next.empty()) start = from;
            if (!next.emplace(from, to).second)
                throw RuntimeFailure("cell union: a piece touches itself at a vertex (internal)");
        };
        for (std::size_t idx : cells) {
            const std::uint64_t r = idx / cols_, c = idx % cols_;
            const int ri = int(r), ci = int(c);
            if (!in(ri + 1, ci)) add(key(r + 1, c), key(r + 1, c + 1));
            if (!in(ri, ci + 1)) add(key(r + 1, c + 1), key(r, c + 1));
            if (!in(ri - 1, ci)) add(key(r, c + 1), key(r, c));
            if (!in(ri, ci - 1)) add(key(r, c), key(r + 1, c));
        }
        Ring ring;
        ring.reserve(next.size());
        std::uint64_t v = start;
        do {
            ring.push_back({xe_[v % w], ye_[v / w]});
            const auto it = next.find(v);
            if (it == next.end()) throw RuntimeFailure("cell union: open boundary (internal)");
            v = it->second;
        } while (v != start && ring.size() <= next.size());
        if (ring.size() != next.size())
            throw RuntimeFailure("cell union: a piece has a hole (internal)");
        return simplified(std::move(ring));
    }

    const std::vector<std::uint8_t>& occ_;
    int rows_, cols_;
    const std::vector<std::int64_t>& xe_;
    const std::vector<std::int64_t>& ye_;
    std::size_t max_vertices_;
    std::vector<std::uint8_t> cut_;
    std::vector<std::uint32_t> label_;
    std::uint32_t next_id_ = 1;
    std::vector<Ring> out_;
};

}  // namespace

std::vector<Ring> union_of_cells(const std::vector<std::uint8_t>& occupied, int rows, int cols,
                                 const std::vector<std::int64_t>& x_edges,
                                 const std::vector<std::int64_t>& y_edges,
                                 std::size_t max_vertices) {
    if (rows < 1 || cols < 1 || occupied.size() != std::size_t(rows) * std::size_t(cols) ||
        x_edges.size() != std::size_t(cols) + 1 || y_edges.size() != std::size_t(rows) + 1)
        throw InvalidInput("union_of_cells: grid and edge table sizes disagree");
    if (max_vertices < 4)
        throw invalid_field("max_vertices", std::to_string(max_vertices), "must be >= 4");
    return CellUnion(occupied, rows, cols, x_edges, y_edges, max_vertices).run();
}

}  // namespace pinmask
