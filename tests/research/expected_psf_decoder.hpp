// The robust-design variant that decodes with the EXPECTED fabricated PSF instead of the design's:
// D = E_s kappa_s J, the kernel OTF averaged over the bias signs times the jitter mean J (what a
// designer who knows the error statistics but not the sign of one copy's bias would decode
// with). The robust-design tests measure it against the nominal-PSF decoder and the robust
// filter of optimize/metrics/robust_wiener; no product figure uses it. Test-only code
// (tests/research's pinmask_research library, which no product target links).
//
// Both figures of a RobustError change against RobustWienerModel::evaluate: `nominal` is the
// NOMINAL capture decoded with D (|G H - 1|^2 S + |G|^2 N sigma^2, G = conj(P^ D / K) w), and
// mse the fabricated captures decoded with it (RobustWienerModel::mismatch_mse with |D|^2 and
// the crosses conj(D) kappa_s J). Without fabrication errors D is the nominal kernel and both
// are the nominal figure.
#pragma once

#include "optimize/metrics/robust_wiener.hpp"

namespace pinmask {

// The fixed-NSR or optimal filter built from D; kTunedNsr is evaluate_expected_psf_tuned_nsr.
RobustError evaluate_expected_psf(const RobustWienerModel& model,
                                  const ComplexPlane& pattern_spectrum, const WienerFilterSpec& f);

// The fixed-NSR filter built from D with the NSR tuned for the nominal capture decoded with D,
// then its robust error; nominal.nsr is that NSR.
RobustError evaluate_expected_psf_tuned_nsr(const RobustWienerModel& model,
                                            const ComplexPlane& pattern_spectrum);

// The frequency response of those filters (RobustWienerModel::filter_response with D; a tuned
// NSR as evaluate_expected_psf_tuned_nsr tunes it).
ComplexPlane expected_psf_filter_response(const RobustWienerModel& model,
                                          const ComplexPlane& pattern_spectrum,
                                          const WienerFilterSpec& f);

}  // namespace pinmask
