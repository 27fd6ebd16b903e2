#include "optimize/search/rerank_order.hpp"

#include <cmath>
#include <numeric>
#include <utility>

#include "core/errors/error.hpp"

namespace pinmask {

bool simulated_clearly_better(const std::vector<double>& b, const std::vector<double>& a) {
    if (a.size() != b.size() || a.empty())
        throw InvalidInput("rerank order: per-scene PSNR lists of different sizes or empty");
    const std::size_t s = a.size();
    double mean = 0.0;
    for (std::size_t i = 0; i < s; ++i) mean += b[i] - a[i];
    mean /= static_cast<double>(s);
    if (s == 1) return mean > 0.0;
    double ss = 0.0;
    for (std::size_t i = 0; i < s; ++i) {
        const double e = (b[i] - a[i]) - mean;
        ss += e * e;
    }
    const double se =
        std::sqrt(ss / static_cast<double>(s - 1)) / std::sqrt(static_cast<double>(s));
    return mean > se;
}

std::vector<std::size_t> rerank_order(const std::vector<std::vector<double>>& psnr) {
    std::vector<std::size_t> order(psnr.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    for (std::size_t pass = 0; pass < psnr.size(); ++pass) {
        bool swapped = false;
        for (std::size_t i = 0; i + 1 < order.size(); ++i) {
            if (simulated_clearly_better(psnr[order[i + 1]], psnr[order[i]])) {
                std::swap(order[i], order[i + 1]);
                swapped = true;
            }
        }
        if (!swapped) break;
    }
    return order;
}

}  // namespace pinmask
