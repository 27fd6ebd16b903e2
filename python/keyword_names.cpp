#include "python/keyword_names.hpp"

#include <array>
#include <utility>

#include "core/errors/field_names.hpp"
#include "core/errors/spelling_table.hpp"

namespace pinmask::py_names {
namespace {

// field name (as the libraries write it) -> keyword argument. Sorted by field name (a test
// checks it). A field whose keyword is its own name needs no row.
constexpr auto kKeywords = std::to_array<SpellingRow>({
    {"chord_tolerance_m", "chord_tol"},
    {"cost_window", "window"},
    {"depth_from_m", "depth_from"},
    {"depth_to_m", "depth_to"},
    {"distances_m", "from_m"},
    {"exact_geometry", "geometry='exact'"},
    {"frame_m", "frame"},
    {"grid_m", "grid"},
    {"hole_side_m", "hole_side"},
    {"iterations", "iters"},
    {"lambda", "lambda_"},
    {"margin_m", "margin"},
    {"max_evaluations", "evals"},
    {"max_snap_error_nm", "max_snap_error"},
    {"no_rerank", "rerank_scenes=[]"},
    {"no_rerank_tv", "rerank_tv=False"},
    {"nonnegative", "nonneg"},
    {"png_dpi", "dpi"},
    {"polygon_sides", "sides"},
    {"prior.count", "prior_scenes"},
    {"tiff_dpi", "dpi"},
    {"time_budget_s", "time"},
    {"tolerance", "tol"},
    {"weights.analytic_wiener", "w_analytic"},
    {"weights.depth", "depth_weight"},
    {"weights.max_sidelobe", "w_max_sidelobe"},
    {"weights.min_spectrum", "w_min_spectrum"},
    {"weights.sidelobe_energy", "w_sidelobe_energy"},
    {"wiener_nsr", "nsr"},
    {"window", "size"},
});

}  // namespace

std::optional<std::string> keyword_spelling(std::string_view field) {
    return std::string(find_spelling(kKeywords, field).value_or(field));
}

std::string spell_keywords(std::string_view message) {
    return spell_fields(message, &keyword_spelling);
}

}  // namespace pinmask::py_names
