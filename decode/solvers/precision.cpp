#include "decode/solvers/precision.hpp"

#include <sstream>

namespace pinmask {

std::string single_precision_problem(const Plane& psf) {
    const double l1 = psf.abs().sum(), sum = psf.sum();
    const double gain = l1 / std::fabs(sum);
    if (psf.size() > 0 && std::isfinite(gain) && fits_single_precision(gain)) return "";
    std::ostringstream s;
    s << "the PSF's values cancel: sum|a| / |sum a| = " << gain << " exceeds float32's safe range "
      << kSingleSafeMagnitude << " (its transfer function would overflow after normalisation)";
    return s.str();
}

}  // namespace pinmask
