#include "cli/options/flag_names.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "core/errors/field_names.hpp"

namespace pinmask::cli {
namespace {

// field name (as the libraries write it) -> flag. Sorted by field name (a test checks it, and
// that every field a library names has a row).
constexpr auto kFlags = std::to_array<std::pair<std::string_view, std::string_view>>({
    {"allow_spectral_zeros", "--allow-spectral-zeros"},
    {"allow_violations", "--allow-violations"},
    {"attempts", "--attempts"},
    {"background", "--background"},
    {"bandwidth_m", "--bandwidth"},
    {"baseline_count", "--baseline-count"},
    {"batch", "--batch"},
    {"bayer", "--bayer"},
    {"bits", "--bits"},
    {"checkpoint", "--checkpoint"},
    {"checkpoint_every", "--checkpoint-every"},
    {"chord_tol", "--chord-tol"},
    {"chord_tolerance_m", "--chord-tol"},
    {"circles", "--circles"},
    {"config", "--config"},
    {"cost_window", "--window"},
    {"crop", "--crop"},
    {"dark", "--dark"},
    {"dark_current", "--dark-current"},
    {"dark_frame", "--dark-frame"},
    {"datatype", "--datatype"},
    {"depth_from_m", "--depth-from"},
    {"depth_to_m", "--depth-to"},
    {"distances_m", "--from/--to"},
    {"draw", "--draw"},
    {"emulsion", "--emulsion"},
    {"energy_fraction", "--energy"},
    {"eps", "--eps"},
    {"exact_geometry", "--geometry exact"},
    {"family", "--family"},
    {"filter", "--filter"},
    {"formats", "--format"},
    {"frame", "--frame"},
    {"frame_m", "--frame"},
    {"from_m", "--from"},
    {"full_sensor", "--full-sensor"},
    {"full_well", "--full-well"},
    {"grid", "--grid"},
    {"grid_m", "--grid"},
    {"hierarchy", "--hierarchy"},
    {"hole_side", "--hole-side"},
    {"hole_side_m", "--hole-side"},
    {"holes", "--holes"},
    {"iterations", "--iters"},
    {"keep_out", "--keep-out"},
    {"kerf", "--kerf"},
    {"kerf_m", "--kerf"},
    {"kernel", "--kernel"},
    {"kernel_path", "--kernel-path"},
    {"lambda", "--lambda"},
    {"layer", "--layer"},
    {"margin", "--margin"},
    {"margin_m", "--margin"},
    {"mask", "--mask"},
    {"max_evaluations", "--evals"},
    {"max_rotation_deg", "--max-rotation"},
    {"max_snap_error", "--max-snap-error"},
    {"max_snap_error_nm", "--max-snap-error"},
    {"max_vertices", "--max-vertices"},
    {"method", "--method"},
    {"metrics", "--metrics"},
    {"migrate_every", "--migrate-every"},
    {"min_feature", "--min-feature"},
    {"min_space", "--min-space"},
    {"mirror", "--mirror"},
    {"model", "--model"},
    {"no_rerank", "--no-rerank"},
    {"no_rerank_tv", "--no-rerank-tv"},
    {"no_sidecar", "--no-sidecar"},
    {"noise_seeds", "--seeds"},
    {"noise_sigma", "--noise-sigma"},
    {"nonnegative", "--nonneg"},
    {"nsr", "--nsr"},
    {"nsr_map", "--nsr-map"},
    {"object_distance_m", "--object-distance"},
    {"objective", "--objective"},
    {"optical_density", "--optical-density"},
    {"photons", "--photons"},
    {"pinhole_m", "--pinhole"},
    {"pitch_range", "--pitch-range"},
    {"pixels_per_cell", "--pixels-per-cell"},
    {"plate_m", "--vendor"},  // the plate size comes with the vendor preset
    {"png_dpi", "--dpi"},
    {"polygon_sides", "--sides"},
    {"precision", "--precision"},
    {"prior", "--prior"},
    {"prior.count", "--prior-scenes"},
    {"psf_stack", "--psf-stack"},
    {"rank_by", "--rank-by"},
    {"read_noise", "--read-noise"},
    {"regulariser", "--regulariser"},
    {"rerank_scenes", "--rerank-scenes"},
    {"resume", "--resume"},
    {"robust", "--robust"},
    {"saturation_level", "--saturation"},
    {"scenes", "--scenes"},
    {"seed", "--seed"},
    {"sensor", "--sensor"},
    {"shape", "--shape"},
    {"sides", "--sides"},
    {"smooth", "--smooth"},
    {"snr_db", "--snr"},
    {"spacing", "--spacing"},
    {"steps", "--steps"},
    {"threads", "--threads"},
    {"threshold_sigmas", "--threshold"},
    {"tiff_dpi", "--dpi"},
    {"tiles", "--tiles"},
    {"time_budget_s", "--time"},
    {"to_m", "--to"},
    {"tolerance", "--tol"},
    {"tone", "--tone"},
    {"top", "--top"},
    {"tv_iterations", "--tv-iters"},
    {"tv_lambda", "--tv-lambda"},
    {"units", "--units"},
    {"vendor", "--vendor"},
    {"weights.analytic_wiener", "--w-analytic"},
    {"weights.depth", "--depth-weight"},
    {"weights.max_sidelobe", "--w-max-sidelobe"},
    {"weights.min_spectrum", "--w-min-spectrum"},
    {"weights.sidelobe_energy", "--w-sidelobe-energy"},
    {"wiener_nsr", "--nsr"},
    {"window", "--size"},
});

}  // namespace

std::optional<std::string> flag_spelling(std::string_view field) {
    const auto it =
        std::lower_bound(kFlags.begin(), kFlags.end(), field,
                         [](const auto& row, std::string_view f) { return row.first < f; });
    if (it == kFlags.end() || it->first != field) return std::nullopt;
    return std::string(it->second);
}

std::string spell_flags(std::string_view message) { return spell_fields(message, &flag_spelling); }

std::span<const std::pair<std::string_view, std::string_view>> flag_rows() { return kFlags; }

}  // namespace pinmask::cli
