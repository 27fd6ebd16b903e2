#include "decode/capture/capture.hpp"

#include <cmath>
#include <exception>
#include <thread>

#include "core/errors/error.hpp"

namespace pinmask {
namespace {

std::string size_text(int rows, int cols) {
    return std::to_string(cols) + " x " + std::to_string(rows) + " (W x H)";
}

// The first non-finite pixel of a plane, named (the full scan runs only once a fast test failed).
void check_plane_finite(const Plane& p, const std::string& what, int ch) {
    if (is_all_finite(p)) return;
    for (Eigen::Index r = 0; r < p.rows(); ++r)
        for (Eigen::Index c = 0; c < p.cols(); ++c)
            if (!std::isfinite(p(r, c))) {
                throw InvalidInput(what + ": pixel (row " + std::to_string(r) + ", col " +
                                   std::to_string(c) + ", channel " + std::to_string(ch) + ") is " +
                                   (std::isnan(p(r, c)) ? "NaN" : "infinite") +
                                   ": every pixel must be finite");
            }
}

}  // namespace

void check_image_finite(const Image& image, const std::string& what) {
    if (image.empty()) throw InvalidInput(what + ": the image is empty (no pixels)");
    for (int ch = 0; ch < image.n_channels(); ++ch)
        check_plane_finite(image.channels[static_cast<std::size_t>(ch)], what, ch);
}

void check_psf(const Plane& psf, const std::string& what) {
    if (psf.size() == 0) throw InvalidInput(what + ": the image is empty (no pixels)");
    // One pixel is a point, not a coded PSF: the cyclic model's window is the PSF's size, so a
    // "decode" returned a 1 x 1 image (exit 0).
    if (psf.size() == 1)
        throw InvalidInput(what +
                           ": the PSF is 1 x 1 pixel: a single point codes nothing and "
                           "the decode would be one pixel; give the PSF the capture was "
                           "taken with");
    // A finite sum proves every value finite; otherwise the scan names the pixel, or the values
    // are finite and their sum overflows (unit-sum normalisation would zero the PSF).
    const double sum = psf.sum();
    if (!std::isfinite(sum)) {
        check_plane_finite(psf, what, 0);
        throw InvalidInput(what + ": the PSF's values (largest " +
                           std::to_string(psf.abs().maxCoeff()) +
                           ") sum beyond the double range: scale the PSF down");
    }
    if (!(sum > 0.0)) {
        throw InvalidInput(what + ": the PSF sums to " + std::to_string(sum) +
                           (psf.abs().maxCoeff() == 0.0 ? " (all zeros)" : "") +
                           ": a PSF must have a positive sum");
    }
}

Image subtract_dark(const Image& capture, const Image& dark) {
    if (dark.rows() != capture.rows() || dark.cols() != capture.cols()) {
        throw InvalidInput("dark frame: size " + size_text(dark.rows(), dark.cols()) +
                           " differs from the capture's " +
                           size_text(capture.rows(), capture.cols()) +
                           ": the dark frame must have the capture's size");
    }
    if (dark.n_channels() != 1 && dark.n_channels() != capture.n_channels()) {
        throw InvalidInput("dark frame: " + std::to_string(dark.n_channels()) +
                           " channels, capture " + std::to_string(capture.n_channels()) +
                           ": the dark frame must have 1 channel or the capture's count");
    }
    Image out = capture;
    for (std::size_t ch = 0; ch < out.channels.size(); ++ch)
        out.channels[ch] -= dark.channels[dark.n_channels() == 1 ? 0 : ch];
    return out;
}

CropWindow crop_window(int frame_rows, int frame_cols, int period_rows, int period_cols,
                       const CropSpec& spec) {
    if (spec.mode == CropMode::kNone) return {0, 0, frame_rows, frame_cols};
    if (period_rows < 1 || period_cols < 1) {
        throw InvalidInput("period: " + size_text(period_rows, period_cols) +
                           ": both sides must be >= 1");
    }
    if (period_rows > frame_rows || period_cols > frame_cols) {
        throw InvalidInput("crop: the capture " + size_text(frame_rows, frame_cols) +
                           " is smaller than one period " + size_text(period_rows, period_cols) +
                           " (the PSF size): the capture must hold at least one full period");
    }
    if (spec.mode == CropMode::kCenter) {
        return {(frame_rows - period_rows) / 2, (frame_cols - period_cols) / 2, period_rows,
                period_cols};
    }
    if (spec.row < 0 || spec.col < 0 || spec.row + period_rows > frame_rows ||
        spec.col + period_cols > frame_cols) {
        throw InvalidInput(
            "crop corner X,Y = " + std::to_string(spec.col) + "," + std::to_string(spec.row) +
            " with period " + size_text(period_rows, period_cols) + " leaves the capture " +
            size_text(frame_rows, frame_cols) + ": need 0 <= X <= W - Pw and 0 <= Y <= H - Ph");
    }
    return {spec.row, spec.col, period_rows, period_cols};
}

Image crop(const Image& image, const CropWindow& w) {
    Image out;
    out.channels.reserve(image.channels.size());
    for (const Plane& p : image.channels)
        out.channels.push_back(p.block(w.row, w.col, w.rows, w.cols));
    return out;
}

std::vector<DecodeResult> decode_channels(const Image& capture, const std::vector<Plane>& psfs,
                                          const DecodeOptions& options,
                                          const std::vector<double>& noise_sigmas) {
    const std::size_t n = capture.channels.size();
    if (psfs.size() != 1 && psfs.size() != n) {
        throw InvalidInput("PSF: " + std::to_string(psfs.size()) + " channels for a capture of " +
                           std::to_string(n) + ": need one PSF or one per channel");
    }
    if (!noise_sigmas.empty() && noise_sigmas.size() != n) {
        throw InvalidInput("decode_channels: " + std::to_string(noise_sigmas.size()) +
                           " noise sigmas for a capture of " + std::to_string(n) + " channels");
    }
    auto psf_of = [&](std::size_t ch) -> const Plane& { return psfs[psfs.size() == 1 ? 0 : ch]; };
    // Each channel's options: the shared ones, or a copy with the channel's noise sigma.
    std::vector<DecodeOptions> own;
    for (double sigma : noise_sigmas) {
        own.push_back(options);
        own.back().auto_noise_sigma = sigma;
    }
    auto options_of = [&](std::size_t ch) -> const DecodeOptions& {
        return own.empty() ? options : own[ch];
    };
    std::vector<DecodeResult> results(n);
    if (n == 1) {
        results[0] = decode_plane(capture.channels[0], psf_of(0), options_of(0));
        return results;
    }
    std::vector<std::exception_ptr> errors(n);
    std::vector<std::thread> threads;
    threads.reserve(n);
    for (std::size_t ch = 0; ch < n; ++ch) {
        threads.emplace_back([&, ch] {
            try {
                results[ch] = decode_plane(capture.channels[ch], psf_of(ch), options_of(ch));
            } catch (...) {
                errors[ch] = std::current_exception();
            }
        });
    }
    for (auto& t : threads) t.join();
    for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
    return results;
}

}  // namespace pinmask
