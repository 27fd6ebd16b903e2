// Fuzzes the image readers (core/image/image_io read_image: TIFF via libtiff, PNG via libpng, JPEG
// via libjpeg-turbo, npy), chosen by magic bytes, through a scratch file. An accepted image must be
// consistent: 1 or 3 channels, every channel of the declared size, within kMaxImageSamples.
#include <cstddef>
#include <cstdint>

#include "core/errors/error.hpp"
#include "core/image/image_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    pinmask::fuzz::set_memory_limit();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace pinmask;
    const auto& path = fuzz::write_scratch(data, size, ".img");
    LoadedImage img;
    try {
        img = read_image(path);
    } catch (const InvalidInput&) {
        return 0;
    }
    const Image& im = img.image;
    if (im.n_channels() != 1 && im.n_channels() != 3) fuzz::invariant_failed("channel count");
    if (im.rows() < 1 || im.cols() < 1) fuzz::invariant_failed("empty image accepted");
    for (const Plane& p : im.channels) {
        if (p.rows() != im.rows() || p.cols() != im.cols()) fuzz::invariant_failed("plane size");
    }
    if (double(im.rows()) * double(im.cols()) * im.n_channels() > double(kMaxImageSamples)) {
        fuzz::invariant_failed("kMaxImageSamples");
    }
    return 0;
}
