#include "optimize/search/island_search.hpp"

#include <numeric>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "optimize/search/chain_codec.hpp"

namespace pinmask {
namespace {

// The best (objective, pattern) of a chain, if it has one.
const TopCandidates::Item* chain_best(const ChainState& s) {
    return s.top.items().empty() ? nullptr : &s.top.items().front();
}

}  // namespace

void IslandOptions::validate() const {
    // Periods up to the largest evaluation budget (1e9 per chain): boundary counts never overflow.
    constexpr std::int64_t kMaxPeriod = 1'000'000'000;
    if (migrate_every < 0 || migrate_every > kMaxPeriod) {
        throw invalid_field(field_ref("migrate_every"), std::to_string(migrate_every),
                            "must be 0 (no migration) to 1e9 evaluations per chain");
    }
    if (checkpoint_every < 0 || checkpoint_every > kMaxPeriod) {
        throw invalid_field(field_ref("checkpoint_every"), std::to_string(checkpoint_every),
                            "must be 0 (no checkpoints) to 1e9 evaluations per chain");
    }
    if (checkpoint_every > 0 && !checkpoint) {
        throw InvalidInput(field_ref("checkpoint_every") + ": needs " + field_ref("checkpoint") +
                           " FILE");
    }
    if (resume_segment < 0) {
        throw invalid_field("resume segment", std::to_string(resume_segment), "must be >= 0");
    }
}

std::int64_t island_segment_length(const IslandOptions& o) {
    return std::gcd(o.migrate_every, o.checkpoint_every);  // gcd(a, 0) = a
}

Bytes migration_message(const std::vector<ChainState>& states) {
    const TopCandidates::Item* best = nullptr;
    for (const ChainState& s : states) {
        const TopCandidates::Item* b = chain_best(s);
        if (b && (!best || TopCandidates::less(*b, *best))) best = b;
    }
    ByteWriter w;
    w.u64(best ? 1 : 0);
    if (best) {
        w.f64(best->objective);
        encode_pattern(w, best->pattern);
    }
    return w.take();
}

SearchSummary run_island_search(RankComm& comm, const SearchObjective& objective,
                                const SearchOptions& options,
                                const std::function<Pattern(std::mt19937_64&)>& sample,
                                const IslandOptions& islands, const std::atomic<bool>* cancel,
                                const SearchProgress& progress) {
    options.validate();
    islands.validate();
    const int rank = comm.rank(), size = comm.size(), threads = options.threads;
    SearchSegments seg;
    seg.every = island_segment_length(islands);
    seg.first_chain = rank * threads;
    seg.first_segment = islands.resume_segment;
    if (!islands.resume.empty()) {
        const std::size_t want = static_cast<std::size_t>(size) * threads;
        if (islands.resume.size() != want) {
            throw invalid_field(field_ref("resume"),
                                std::to_string(islands.resume.size()) + " chains",
                                "the run has " + std::to_string(want) + " (ranks x threads)");
        }
        const auto b = islands.resume.begin() + static_cast<std::ptrdiff_t>(rank) * threads;
        seg.resume.assign(b, b + threads);
    }
    if (seg.every > 0) {
        seg.at_boundary = [&](const SearchSegments::Boundary& b, std::vector<ChainState>& states) {
            // Every rank takes the same branches: the decisions are collective.
            const bool stop = comm.any(b.stopping);
            const bool all_finished = !comm.any(!b.finished);
            if (stop || all_finished) return false;
            const std::int64_t at = b.segment * seg.every;
            if (islands.migrate_every > 0 && at % islands.migrate_every == 0) {
                const Bytes in = comm.ring_shift(migration_message(states));
                ByteReader r(in);
                if (r.u64() != 0) {
                    const double objective = r.f64();
                    const Pattern p = decode_pattern(r);
                    r.expect_done();
                    for (ChainState& s : states) {
                        const TopCandidates::Item* own = chain_best(s);
                        if (options.strategy == SearchStrategy::kAnneal &&
                            (!own || objective < own->objective))
                            s.start = p;
                    }
                }
            }
            if (islands.checkpoint_every > 0 && at % islands.checkpoint_every == 0) {
                const std::vector<Bytes> all = comm.gather(encode_chain_states(states), 0);
                if (rank == 0) {
                    std::vector<ChainState> every;
                    for (const Bytes& bytes : all)
                        for (ChainState& s : decode_chain_states(bytes))
                            every.push_back(std::move(s));
                    islands.checkpoint(b.segment, seg.every, every);
                }
            }
            return true;
        };
    }
    // Progress on rank 0 counts every rank: the ranks run the same number of chains on the same
    // budget, so rank 0's count times the ranks (exact in the summary, gathered at the end).
    const SearchProgress scaled = [&](const SearchLogRow& row, double fraction) {
        if (!progress) return;
        SearchLogRow all = row;
        all.evaluations *= size;
        progress(all, fraction);
    };
    const bool plain = size == 1 && seg.every == 0 && seg.resume.empty();
    SearchSummary local =
        run_search(objective, options, sample, cancel, scaled, plain ? nullptr : &seg);
    if (size == 1) return local;
    const bool cancelled = comm.any(cancel && cancel->load());
    const std::vector<Bytes> all = comm.gather(encode_chain_states(local.chain_states), 0);
    if (rank != 0) return local;
    std::vector<ChainState> every;
    for (const Bytes& bytes : all)
        for (ChainState& s : decode_chain_states(bytes)) every.push_back(std::move(s));
    SearchSummary merged = summarize_chains(objective, options, std::move(every), cancelled);
    merged.log = std::move(local.log);
    for (SearchLogRow& row : merged.log) row.evaluations *= size;
    merged.seconds = local.seconds;
    return merged;
}

}  // namespace pinmask
