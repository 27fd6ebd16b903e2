// `score MASK --robust SPEC --robust-decoder DIR`: the robust design's decoder (the filter
// minimising the expected fabricated error, optimize/metrics/robust_wiener.hpp
// robust_decoder_inputs) as files `pinmask decode` reads:
//   DIR/robust-psf.tiff  the expected fabricated PSF (float32, sum 1), with DIR/robust-psf.npy
//                        (float64, the exact values) and the sidecar DIR/robust-psf.json
//   DIR/robust-nsr.npy   the per-frequency NSR (float64, period x period, fft2 order)
// decoded by `decode CAPTURE --psf DIR/robust-psf.npy --nsr-map DIR/robust-nsr.npy`. All four
// files appear together or not at all; DIR (and missing parents) is created.
#pragma once

#include <string>
#include <vector>

#include "design/pattern/mask.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scene_prior.hpp"

namespace pinmask::cli {

struct RobustDecoderFiles {
    std::string psf_tiff, psf_npy, sidecar, nsr_npy;
    int floored = 0;  // frequencies where decode's deconvwnr floor departs from the filter
};

// Refusals before any work (InvalidInput naming --robust-decoder): not exactly one mask (`masks`,
// the inputs) or one noise level (the filter depends on both), an empty name, a DIR that is a
// file, an unwritable place, an output that is one of the masks.
void check_robust_decoder_request(const std::string& dir, const std::vector<std::string>& masks,
                                  std::size_t noise_levels);

// Computes and writes the files for `mask` (read from mask_path) under errors, prior and noise.
RobustDecoderFiles write_robust_decoder_files(const std::string& dir, const Mask& mask,
                                              const std::string& mask_path,
                                              const FabricationErrors& errors,
                                              const ScenePrior& prior, const NoiseModel& noise);

// The two commands that use them, for the summary.
std::string robust_decoder_usage(const RobustDecoderFiles& f, const std::string& mask_path);

}  // namespace pinmask::cli
