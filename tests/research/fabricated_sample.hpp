// Fabricated masks drawn at random (the error model of optimize/metrics/robust_errors.hpp): one
// draw is the PSF a fabricated copy of the mask really has, on the m x m torus in design/psf/psf's
// frame (same kernel placement, same 1/K weights up to the missing-pinhole scaling), so the nominal
// PSF decodes its captures exactly as an uncalibrated camera would. This is the fixed-seed
// Monte-Carlo sample the closed form (optimize/metrics/robust_wiener) is tested against, and the
// simulated robust figure of the robust-design tests. Test-only code (tests/research's
// pinmask_research library, which no product target links).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "design/psf/kernel.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/robust_sample.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/simulate/noise_model.hpp"

namespace pinmask {

class FabricationSampler {
  public:
    // The mask needs at least one pinhole; errors validated against it (fabricated_kernels).
    FabricationSampler(const Mask& mask, FabricationErrors errors,
                       const KernelOptions& options = {});

    int period() const { return m_; }

    // One fabricated PSF, m x m. Draw order (fixed, so one seed gives one PSF): the bias sign
    // (only when b > 0; + for u < 1/2), then per pinhole in pattern order: missing (uniform < q,
    // only when q > 0), row shift, column shift (normal, only when sigma > 0). Each present
    // pinhole adds its kernel with weight 1 / ((1 - q) K), area-resampled to its shifted place.
    Plane draw(std::mt19937_64& rng) const;

  private:
    Mask mask_;
    FabricationErrors errors_;
    std::vector<Kernel> kernels_;
    double sigma_px_ = 0.0;
    int m_ = 0;
};

// Simulated Wiener decoding of fabricated masks: for draw i (std::mt19937_64 seeded with
// (seed, i)), every scene channel is captured through the draw's PSF (optimize/simulate/simulate
// cyclic_capture), noise added (optimize/simulate/noise_model, the pattern's K and n^2), and
// decoded by the fixed-NSR Wiener filter of the NOMINAL PSF. PSNR per scene from the MSE averaged
// over draws and channels; the figure is the mean over scenes. `nominal_psnr_db` is the same with
// the nominal PSF in place of each draw (same noise draws), so nominal - fabricated is the loss.
struct FabricatedQuality {
    double nominal_psnr_db = 0.0;
    double fabricated_psnr_db = 0.0;
    int draws = 0;
};
FabricatedQuality fabricated_wiener_quality(const Mask& mask, const FabricationErrors& errors,
                                            const std::vector<NamedScene>& scenes,
                                            const NoiseModel& noise, double nsr, int draws,
                                            std::uint64_t seed);

// The same (same draws, noise and scenes) decoded by a fixed linear filter given as its m x m
// frequency response G (X~ = G C^ on the capture's unnormalised DFT, real part of the inverse
// DFT kept), e.g. RobustWienerModel's robust_filter_response or optimal_filter_response.
// InvalidInput when G is not m x m.
FabricatedQuality fabricated_filter_quality(const Mask& mask, const FabricationErrors& errors,
                                            const std::vector<NamedScene>& scenes,
                                            const NoiseModel& noise, const ComplexPlane& response,
                                            int draws, std::uint64_t seed);

}  // namespace pinmask
