// What `pinmask search` writes into its output folder, all staged together (all or nothing):
//   rank-1.mask.json ... rank-N.mask.json   candidates, best first, with provenance and scores
//   run-log.csv    evaluations_per_chain, evaluations, best_objective at fixed evaluation
//                  counts: byte-identical for the same --evals run
//   summary.md     the ranking table, the termination, spectral-zero flags; with a time budget
//                  also planned vs used time (with --evals no timings: byte-identical)
//   timing.csv     seconds, evaluations, best_objective sampled by wall clock (never identical)
//   search.config.json                      the resolved configuration of the run
// With --holes A..B also:
//   holes.csv      K, light gain, objective, predicted (analytic) Wiener PSNR, spectral zero,
//                  geometry hash of the best mask at each K, and the upper bound on the analytic
//                  PSNR of any pattern with that K (optimize/search/objective_bound; summary.md
//                  holds the same table and "best possible for K holes <= X dB")
//   holes.svg, holes.png   predicted PSNR against K, light gain K beside it (report/holes_plot)
//   best-K<K>.mask.json    the best mask at each K
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "optimize/search/search_pipeline.hpp"

namespace pinmask::cli {

// Writes the folder's files; returns the mask paths in rank order.
std::vector<std::filesystem::path> write_search_outputs(const std::filesystem::path& dir,
                                                        const SearchPipelineSummary& summary,
                                                        const nlohmann::ordered_json& config);

// The Markdown summary (also printed by the command).
std::string search_summary_markdown(const SearchPipelineSummary& summary);

// --explain's line: which frequencies the prior makes irrelevant, and what was skipped.
std::string search_explain_text(const SearchPipelineSummary& s, bool allow_spectral_zeros);

// Checks every file a search writes into dir before any work (core/files/output_set plan_outputs):
// the run log, summary, timing, config and best-so-far snapshot, and with `per_holes` the per-K
// table and plot; `config` is the --config input. (rank-N.mask.json are checked when staged.)
void plan_search_outputs(const std::filesystem::path& dir, bool per_holes,
                         const std::string& config);

}  // namespace pinmask::cli
