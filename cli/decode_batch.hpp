// `pinmask decode --batch LIST_OR_DIR -o DIR`: many captures, one PSF, the same
// flags. The inputs: io/capture_list (a directory or a list file). DIR is created when missing
// (core/files/output_folder) and removed again when the run fails. For each capture
// DIR/STEM.EXT (EXT from --batch-format), DIR/STEM.EXT.config.json and with --batch-stats
// DIR/STEM.stats.json, the same files `pinmask decode CAPTURE -o DIR/STEM.EXT` writes;
// DIR/batch-summary.json lists every capture in input order (deterministic: no timings, no rank
// count).
//
// Ranks (RankComm): capture i is decoded by rank i % size; each rank stages its own files, rank 0
// gathers the per-capture results and stages the summary, and every rank commits only when no
// rank failed: an error anywhere leaves no file. The bytes do not depend on the rank count.
//
// Time budget (PINMASK_TIME_LIMIT, core/limits/resource_limits): each rank checks it between its
// captures (its first capture always runs). Once it is spent the rank stops; the captures
// finished on every rank are written as usual, the summary lists the others with "output": null
// and "not_done" (the reason), plus "stopped": {reason, done, not_done}. Then one process throws
// TimeLimitSpent (exit 3); under mpirun rank 0 prints why and every rank throws
// BatchQuietExit{3}.
#pragma once

#include <string>
#include <vector>

#include "cli/outputs/decode_output.hpp"
#include "core/image/raw_io.hpp"
#include "optimize/search/rank_comm.hpp"

namespace pinmask::cli {

struct BatchRequest {
    std::string list;             // --batch: a directory or a list file
    std::string format = "tiff";  // --batch-format: tiff | png | npy
    bool stats = false;           // --batch-stats
};

// Thrown on ranks other than 0 when the batch failed on some rank: rank 0 reports the error,
// the others leave with `code` after their staged files are discarded.
struct BatchQuietExit {
    int code;
};

// Runs the batch on every rank of `comm` (r: the decode flags, r.output the directory). Prints
// (rank 0 only) one line per capture and the summary path, or the summary JSON with --json.
void run_decode_batch(const DecodeCommand& r, const BatchRequest& b, BayerMode bayer,
                      RankComm& comm);

}  // namespace pinmask::cli
