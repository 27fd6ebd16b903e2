#include "cli/outputs/compare_report.hpp"

#include <algorithm>
#include <sstream>

namespace pinmask::cli {

std::string compare_table_text(const ReportTable& t) {
    std::vector<std::size_t> w(t.headers.size(), 0);
    for (std::size_t c = 0; c < t.headers.size(); ++c) {
        w[c] = std::max(t.headers[c].size(), t.units[c].size());
        for (const auto& row : t.rows) w[c] = std::max(w[c], row[c].size());
    }
    std::ostringstream s;
    auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t c = 0; c < cells.size(); ++c) {
            const std::string pad(w[c] - cells[c].size(), ' ');
            s << (c == 0 ? cells[c] + pad : "  " + pad + cells[c]);
        }
        s << "\n";
    };
    line(t.headers);
    line(t.units);
    for (const auto& row : t.rows) line(row);
    return s.str();
}

}  // namespace pinmask::cli
