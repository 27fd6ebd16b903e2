#include "decode/capture/batch.hpp"

#include <string>
#include <utility>

#include "core/errors/error.hpp"

namespace pinmask {

BatchDecoder::BatchDecoder(CaptureDecodeInputs shared, CaptureDecodeOptions options)
    : shared_(std::move(shared)),
      options_(std::move(options)),
      plans_(std::make_unique<DecodePlanCache>()) {
    options_.validate();
    options_.decode.plans = plans_.get();
}

CaptureDecodeResult BatchDecoder::decode(Image capture) {
    CaptureDecodeInputs in;
    in.capture = std::move(capture);
    in.psf = shared_.psf;
    in.psf_counts = shared_.psf_counts;
    in.dark = shared_.dark;
    in.psf_one_period = shared_.psf_one_period;
    CaptureDecodeResult r = decode_capture(std::move(in), options_);
    ++decoded_;
    return r;
}

std::vector<std::size_t> batch_share(std::size_t n, int rank, int size) {
    if (size < 1) throw invalid_field("size", std::to_string(size), "must be >= 1");
    if (rank < 0 || rank >= size)
        throw invalid_field("rank", std::to_string(rank), "must be 0.." + std::to_string(size - 1));
    std::vector<std::size_t> mine;
    for (std::size_t i = static_cast<std::size_t>(rank); i < n; i += static_cast<std::size_t>(size))
        mine.push_back(i);
    return mine;
}

}  // namespace pinmask
