#include "decode/solvers/plan_cache.hpp"

#include "decode/solvers/tikhonov.hpp"

namespace pinmask {
namespace {

bool same_geometry(const ConvGeometry& a, const ConvGeometry& b) {
    return a.model == b.model && a.capture_rows == b.capture_rows &&
           a.capture_cols == b.capture_cols && a.work_rows == b.work_rows &&
           a.work_cols == b.work_cols && a.crop_row == b.crop_row && a.crop_col == b.crop_col;
}

bool same_plane(const Plane& a, const Plane& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() && (a == b).all();
}

}  // namespace

std::shared_ptr<const ConvolutionOperator> DecodePlanCache::conv_operator(const Plane& psf,
                                                                          const ConvGeometry& g) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const OperatorEntry& e : operators_)
        if (same_geometry(e.g, g) && same_plane(e.psf, psf)) return e.op;
    auto op = std::make_shared<const ConvolutionOperator>(psf, g);
    operators_.push_back({psf, g, op});
    return op;
}

std::shared_ptr<const WienerFilter> DecodePlanCache::filter(const Plane& psf, const ConvGeometry& g,
                                                            const DecodeOptions& o) {
    const bool wiener = o.method == DecodeMethod::kWiener;
    const double parameter = wiener ? o.wiener.nsr : o.tikhonov.lambda;
    std::lock_guard<std::mutex> lock(mutex_);
    for (const FilterEntry& e : filters_) {
        if (e.method == o.method && e.parameter == parameter &&
            (wiener || e.regulariser == o.tikhonov.regulariser) && same_geometry(e.g, g) &&
            same_plane(e.psf, psf))
            return e.filter;
    }
    // Built from the operator's OTF as an uncached decode builds it (decoder.hpp
    // closed_form_filter), so a cached decode gives the same bytes; an operator already in the
    // cache is used, else a temporary one (the operator count is conv_operator's alone).
    std::shared_ptr<const ConvolutionOperator> op;
    for (const OperatorEntry& e : operators_)
        if (same_geometry(e.g, g) && same_plane(e.psf, psf)) op = e.op;
    if (!op) op = std::make_shared<const ConvolutionOperator>(psf, g);
    auto f = std::make_shared<const WienerFilter>(closed_form_filter(*op, o));
    filters_.push_back({psf, g, o.method, parameter, o.tikhonov.regulariser, f});
    return f;
}

int DecodePlanCache::operators_built() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<int>(operators_.size());
}

int DecodePlanCache::filters_built() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<int>(filters_.size());
}

}  // namespace pinmask
