#include "cli/outputs/compare_report.hpp"

#include <algorithm>
#include <sstream>

#include "cli/options/analytic_setup.hpp"
#include "io/json_strict.hpp"

namespace pinmask::cli {

using io::json_strict::finite_or_null;

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

nlohmann::ordered_json compare_row_json(const CompareRow& r) {
    nlohmann::ordered_json j{{"name", r.name},
                             {"kind", r.kind},
                             {"source", r.source},
                             {"geometry_hash", r.geometry_hash},
                             {"n", r.n},
                             {"holes", r.holes},
                             {"pixels_per_cell", r.pixels_per_cell},
                             {"period_px", r.period_px},
                             {"min_spacing_cells", r.min_spacing_cells},
                             {"spacing_ok", r.spacing_ok},
                             {"spacing_violations", r.spacing_violations},
                             {"analytic_wiener_psnr_db", finite_or_null(r.analytic_wiener_psnr_db)},
                             {"wiener_psnr_db", finite_or_null(r.wiener_psnr_db)},
                             {"wiener_ssim", finite_or_null(r.wiener_ssim)},
                             {"wiener_nsr", r.wiener_nsr},
                             {"tv_psnr_db", finite_or_null(r.tv_psnr_db)},
                             {"tv_ssim", finite_or_null(r.tv_ssim)},
                             {"tv_lambda", r.tv_lambda}};
    metrics_json(r.metrics, j);  // every level with score's keys
    return j;
}

}  // namespace pinmask::cli
