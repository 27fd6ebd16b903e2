#include "design/optics/distance_list.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/errors/error.hpp"
#include "core/units/number_format.hpp"

namespace pinmask {

void check_distinct_distances(const std::vector<double>& u, const std::string& field) {
    std::vector<std::size_t> order(u.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return u[a] < u[b]; });
    for (std::size_t k = 1; k < order.size(); ++k) {
        const double ua = u[order[k - 1]], ub = u[order[k]];
        const bool same = ua == ub || (std::isfinite(ub) && ub - ua <= kSameDistanceRelative * ub);
        if (!same) continue;
        const std::size_t first = std::min(order[k - 1], order[k]);
        const std::size_t second = std::max(order[k - 1], order[k]);
        throw invalid_field(
            field, format_number(u[first], 17) + " m and " + format_number(u[second], 17) + " m",
            "planes " + std::to_string(first) + " and " + std::to_string(second) +
                " hold the same distance twice: they differ by less than " +
                format_number(kSameDistanceRelative) + " of it, which no capture can tell apart");
    }
}

}  // namespace pinmask
