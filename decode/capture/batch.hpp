// Batch decode: many captures with one PSF and one set of options. The PSF, the dark
// frame and the options are given once; each decode() runs decode_capture (the pipeline of
// `pinmask decode`) with a plan cache (decode/solvers/plan_cache.hpp), so the OTF, the closed-form
// filter and their FFT plans are made once per working grid and reused by every capture of that
// size. A capture decoded here gives the same bytes as decode_capture on it alone. Never prints,
// never touches files; the CLI (cli/decode_batch.cpp) loads and writes.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "decode/capture/capture_pipeline.hpp"
#include "decode/solvers/plan_cache.hpp"

namespace pinmask {

class BatchDecoder {
  public:
    // `shared`: the PSF (and psf_counts, dark) of every capture; its capture is ignored.
    // Options are validated here (InvalidInput naming the field).
    BatchDecoder(CaptureDecodeInputs shared, CaptureDecodeOptions options);

    // decode_capture({capture, PSF, counts, dark}, options) with the shared plans.
    CaptureDecodeResult decode(Image capture);

    const DecodePlanCache& plans() const { return *plans_; }
    const CaptureDecodeInputs& shared() const { return shared_; }
    int decoded() const { return decoded_; }

  private:
    CaptureDecodeInputs shared_;
    CaptureDecodeOptions options_;
    std::unique_ptr<DecodePlanCache> plans_;
    int decoded_ = 0;
};

// The captures rank `rank` of `size` decodes: indices i < n with i % size == rank (round robin
// by input order). InvalidInput for size < 1 or rank outside 0..size-1.
std::vector<std::size_t> batch_share(std::size_t n, int rank, int size);

}  // namespace pinmask
