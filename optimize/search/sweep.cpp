#include "optimize/search/sweep.hpp"

#include <cstring>
#include <type_traits>

#include "core/errors/error.hpp"
#include "optimize/search/work_queue.hpp"

namespace pinmask {
namespace {

// A byte writer and reader of plain values (native layout) and length-prefixed strings.
struct Writer {
    std::string out;
    template <class T>
    void put(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void put_string(const std::string& s) {
        put<std::uint64_t>(s.size());
        out += s;
    }
};

struct Reader {
    std::string_view in;
    std::size_t at = 0;
    void need(std::size_t bytes) const {
        if (bytes > in.size() - at)
            throw RuntimeFailure("sweep: a point's result message is truncated (" +
                                 std::to_string(in.size()) + " bytes)");
    }
    template <class T>
    T get() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, in.data() + at, sizeof v);
        at += sizeof v;
        return v;
    }
    std::string get_string() {
        const auto size = get<std::uint64_t>();
        need(size);
        std::string s(in.substr(at, size));
        at += size;
        return s;
    }
};

// Guards the decoder against a message of another kind or version.
constexpr std::uint32_t kResultMagic = 0x53575031;  // "SWP1"

}  // namespace

std::string encode_sweep_result(const SweepPointResult& r) {
    Writer w;
    w.put(kResultMagic);
    w.put<std::int32_t>(r.pattern.n);
    w.put<std::int32_t>(r.pattern.tiles_rows);
    w.put<std::int32_t>(r.pattern.tiles_cols);
    w.put(r.pattern.min_spacing_cells);
    w.put<std::uint64_t>(r.pattern.pinholes.size());
    for (const Cell& c : r.pattern.pinholes) {
        w.put<std::int32_t>(c.row);
        w.put<std::int32_t>(c.col);
    }
    w.put<std::uint64_t>(r.scores.size());
    for (const auto& kv : r.scores) {
        w.put_string(kv.first);
        w.put(kv.second);
    }
    w.put(r.objective);
    w.put<std::uint8_t>(r.reranked ? 1 : 0);
    w.put(r.evaluations);
    w.put_string(r.kernel_resolved);
    return w.out;
}

SweepPointResult decode_sweep_result(std::string_view bytes) {
    Reader rd{bytes};
    if (rd.get<std::uint32_t>() != kResultMagic)
        throw RuntimeFailure("sweep: a point's result message has the wrong magic");
    SweepPointResult r;
    r.pattern.n = rd.get<std::int32_t>();
    r.pattern.tiles_rows = rd.get<std::int32_t>();
    r.pattern.tiles_cols = rd.get<std::int32_t>();
    r.pattern.min_spacing_cells = rd.get<double>();
    const auto holes = rd.get<std::uint64_t>();
    rd.need(holes * 2 * sizeof(std::int32_t));
    for (std::uint64_t i = 0; i < holes; ++i) {
        const int row = rd.get<std::int32_t>();
        r.pattern.pinholes.push_back({row, rd.get<std::int32_t>()});
    }
    const auto scores = rd.get<std::uint64_t>();
    for (std::uint64_t i = 0; i < scores; ++i) {
        std::string key = rd.get_string();
        r.scores[key] = rd.get<double>();
    }
    r.objective = rd.get<double>();
    r.reranked = rd.get<std::uint8_t>() != 0;
    r.evaluations = rd.get<std::int64_t>();
    r.kernel_resolved = rd.get_string();
    if (rd.at != bytes.size())
        throw RuntimeFailure("sweep: a point's result message has trailing bytes");
    return r;
}

SweepPointResult run_sweep_point(const SearchPipelineOptions& options) {
    const SearchPipelineSummary s = run_search_pipeline(options);
    if (s.ranked.empty()) throw RuntimeFailure("sweep: the point's search kept no candidate");
    const RankedMask& best = s.ranked.front();
    SweepPointResult r;
    r.pattern = best.mask.pattern;
    r.scores = best.mask.provenance.scores;
    r.objective = best.objective;
    r.reranked = best.reranked;
    r.evaluations = s.search.evaluations;
    r.kernel_resolved = s.kernel_resolved;
    return r;
}

Mask sweep_best_mask(const SearchPipelineOptions& options, const SweepPointResult& r) {
    Mask m = options.tmpl;
    m.pattern = r.pattern;
    m.provenance.seed = options.search.seed;
    m.provenance.generator = options.generator;
    m.provenance.family =
        std::string("search:") +
        (options.search.strategy == SearchStrategy::kRandom ? "random" : "anneal");
    m.provenance.scores = r.scores;
    m.provenance.objective_figure = objective_figure_name(options);
    return m;
}

std::vector<SweepPointResult> run_sweep(RankComm& comm,
                                        const std::vector<SearchPipelineOptions>& points,
                                        const SweepProgress& progress) {
    const WorkQueueResult q = run_work_queue(
        comm, static_cast<int>(points.size()),
        [&](int i) { return encode_sweep_result(run_sweep_point(points[i])); }, progress);
    if (q.failed_index >= 0) {
        const std::string msg = "point " + std::to_string(q.failed_index) + ": " + q.failure;
        if (q.failure_invalid_input) throw InvalidInput(msg);
        throw RuntimeFailure(msg);
    }
    std::vector<SweepPointResult> out;
    for (const std::string& bytes : q.results) out.push_back(decode_sweep_result(bytes));
    return out;
}

}  // namespace pinmask
