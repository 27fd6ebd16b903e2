// The order of re-ranked search candidates: the objective's order stands unless the simulation
// tells two candidates apart. Candidate b moves above a only when b's simulated PSNR is higher by
// more than the standard error of the difference: with d_s = psnr_b(s) - psnr_a(s) over the S
// scenes (paired: the same scenes and noise draws), mean(d) > SE = sd(d) / sqrt(S), sd with
// S - 1 (one scene: no spread known, any positive difference counts). Differences within their
// standard error are noise of the simulation, not evidence, so the objective decides.
// Applied as adjacent swaps, pass after pass, until no swap is left or n passes were made (n
// candidates; the relation need not be transitive, the bound keeps the result defined).
#pragma once

#include <cstddef>
#include <vector>

namespace pinmask {

// Whether b beats a clearly (the rule above). Both vectors hold one PSNR per scene, same size.
bool simulated_clearly_better(const std::vector<double>& b, const std::vector<double>& a);

// psnr[i]: candidate i's per-scene simulated PSNR, candidates in the objective's order (best
// first). Returns the new order as indices into psnr.
std::vector<std::size_t> rerank_order(const std::vector<std::vector<double>>& psnr);

}  // namespace pinmask
