// Decode plans made once and reused across captures (batch decode): the convolution
// operator (the PSF's OTF on the working grid, with its FFT plans) and the closed-form filters
// (Wiener with a scalar NSR, Tikhonov). decode_plane looks them up here when
// DecodeOptions::plans is set; a miss builds the object exactly as an uncached decode does, so a
// cached decode gives the same bytes as a fresh one.
//
// Key: the PSF plane's values (compared exactly, a copy is kept), the convolution geometry, the
// method and its filter parameter. Thread-safe (channels decode in parallel); entries are shared
// and immutable. The counters say how many objects were built (tests check "made once").
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "core/image/image.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/convolution.hpp"
#include "decode/solvers/wiener.hpp"

namespace pinmask {

class DecodePlanCache {
  public:
    // The operator A for (psf, g), built on a miss.
    std::shared_ptr<const ConvolutionOperator> conv_operator(const Plane& psf,
                                                             const ConvGeometry& g);
    // The Wiener (scalar o.wiener.nsr) or Tikhonov filter of o.method for (psf, g).
    std::shared_ptr<const WienerFilter> filter(const Plane& psf, const ConvGeometry& g,
                                               const DecodeOptions& o);

    int operators_built() const;
    int filters_built() const;

  private:
    struct OperatorEntry {
        Plane psf;
        ConvGeometry g;
        std::shared_ptr<const ConvolutionOperator> op;
    };
    struct FilterEntry {
        Plane psf;
        ConvGeometry g;
        DecodeMethod method;
        double parameter;  // nsr or lambda
        TikhonovRegulariser regulariser;
        std::shared_ptr<const WienerFilter> filter;
    };
    mutable std::mutex mutex_;
    std::vector<OperatorEntry> operators_;
    std::vector<FilterEntry> filters_;
};

}  // namespace pinmask
