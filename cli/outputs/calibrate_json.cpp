#include "cli/outputs/calibrate_json.hpp"

#include <cmath>

namespace pinmask::cli {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

Json cells_json(const std::vector<Cell>& cells) {
    Json a = Json::array();
    for (const Cell& c : cells) a.push_back({c.row, c.col});
    return a;
}

}  // namespace

Json calibration_result_json(const calibrate::CalibrationSummary& s, const fs::path& dir) {
    Json j;
    j["rotation_deg"] = s.rotation_deg;
    j["rotation_sigma_deg"] = s.rotation_sigma_deg;
    j["pitch_px"] = {s.pitch_x_px, s.pitch_y_px};
    j["pitch_sigma_px"] = {s.pitch_x_sigma_px, s.pitch_y_sigma_px};
    j["position_px"] = {s.position_x_px, s.position_y_px};
    j["position_sigma_px"] = s.position_sigma_px;
    j["first_full_tile"] = {s.first_tile.row, s.first_tile.col};
    j["fit_residual_rms_px"] = s.fit.residual_rms_px;
    j["pinholes_in_frame"] = s.match.pinholes.size();
    j["missing_pinholes"] = cells_json(s.missing);
    j["merged_pinholes"] = cells_json(s.merged);
    j["oversized_pinholes"] = cells_json(s.oversized);
    Json extra = Json::array();
    for (int k : s.match.extra_spots) extra.push_back({s.spots[k].x, s.spots[k].y});
    j["extra_spots"] = extra;
    j["saturated_spots"] = s.saturated_spots.size();
    j["background"] = s.background;
    j["optical_density"] = std::isfinite(s.optical_density) ? Json(s.optical_density) : Json();
    j["dark_level"] = std::isfinite(s.dark_level) ? Json(s.dark_level) : Json();
    j["dark_source"] = s.dark_source;
    j["noise_sigma"] = s.noise_sigma;
    Json fit = Json::object(), unavailable = Json::object();
    for (const auto& f : s.kernel_fit) {
        if (f.available)
            fit[f.model] = f.residual;
        else
            unavailable[f.model] = f.reason;
    }
    j["kernel_fit"] = fit;
    j["kernel_models_unavailable"] = unavailable;
    j["kernel_best_model"] = s.best_model;
    j["kernel_spots_used"] = s.kernel.spots_used;
    j["psf"] = (dir / "psf.tiff").string();
    j["psf_period"] = s.psfs.period ? Json((dir / "psf-period.tiff").string()) : Json();
    j["psf_period_note"] = s.psfs.period_reason;
    j["kernel"] = (dir / "kernel.tiff").string();
    j["mask"] = (dir / "calibrated.mask.json").string();
    j["report"] = (dir / "report.pdf").string();
    return j;
}

}  // namespace pinmask::cli
