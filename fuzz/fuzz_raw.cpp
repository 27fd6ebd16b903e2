// Fuzzes the camera RAW reader (core/image/raw_io read_raw through LibRaw) in every Bayer mode,
// through a scratch .dng file. An accepted image must be consistent: one channel of a positive size
// within kMaxImageSamples, finite values, a positive full scale. Seeds: fuzz/corpus/raw/
// (tests/bad-inputs/generate.py writes the DNG seed).
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/errors/error.hpp"
#include "core/image/raw_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const auto& path = fuzz::write_scratch(data, size, ".dng");
    const BayerMode mode =
        size > 0 ? static_cast<BayerMode>(data[size - 1] % 4) : BayerMode::kSum2x2;
    LoadedImage img;
    try {
        img = read_raw(path, mode);
    } catch (const InvalidInput&) {
        return 0;
    }
    const Image& im = img.image;
    if (im.n_channels() != 1) fuzz::invariant_failed("channel count");
    if (im.rows() < 1 || im.cols() < 1) fuzz::invariant_failed("empty image accepted");
    if (double(im.rows()) * double(im.cols()) > double(kMaxImageSamples))
        fuzz::invariant_failed("kMaxImageSamples");
    if (!is_all_finite(im.channels[0])) fuzz::invariant_failed("non-finite value");
    if (!(img.full_scale > 0)) fuzz::invariant_failed("full scale");
    return 0;
}
