// `pinmask score --json` from the score transaction's result (optimize/metrics/score_run): one
// row per mask (score's keys for every noise level, per-scene figures, infinities as null), the
// settings and, when asked, the account of what was run. The command prints it; Python's score()
// returns it.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "optimize/metrics/score_run.hpp"

namespace pinmask::io {

// One row: the mask, its geometry and its metrics (io/metrics_json).
nlohmann::ordered_json score_row_json(const ScoreRow& row);

// {masks: rows, settings, explain (with `explain`)}; `rows` as score_row_json gave them (a face
// may have added its robust decoder's files).
nlohmann::ordered_json score_json(const ScoreReport& report,
                                  const std::vector<nlohmann::ordered_json>& rows, bool explain);

}  // namespace pinmask::io
