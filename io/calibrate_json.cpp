#include "io/calibrate_json.hpp"

#include <cmath>

#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "decode/calibrate/report.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/mask_json.hpp"
#include "io/psf_files.hpp"

namespace pinmask::io {

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
    const calibrate::ForwardFit& f = s.fit;
    Json j;
    j["rotation_convention"] =
        "counter-clockwise on screen with rows running down (scipy.ndimage.rotate's sense)";
    j["rotation_deg"] = s.rotation_deg;
    j["rotation_sigma_deg"] = s.rotation_sigma_deg;
    j["pitch_px"] = {s.pitch_x_px, s.pitch_y_px};
    j["pitch_sigma_px"] = {s.pitch_x_sigma_px, s.pitch_y_sigma_px};
    j["design_pitch_px"] = s.design_pitch_px;
    j["position_px"] = {s.position_x_px, s.position_y_px};
    j["position_sigma_px"] = s.position_sigma_px;
    j["first_full_tile"] = {s.first_tile.row, s.first_tile.col};
    j["kernel_family"] = kernel_model_name(f.family);
    j["pinhole_side_m"] = f.side_m;
    j["pinhole_side_scale"] = f.side_scale;
    j["pinhole_side_scale_sigma"] = f.side_scale_sigma;
    int in_frame = 0;
    Json pinholes = Json::array();
    for (const auto& p : f.pinholes) {
        in_frame += p.in_frame ? 1 : 0;
        pinholes.push_back({{"cell", {p.mask_cell.row, p.mask_cell.col}},
                            {"position_px", {p.x, p.y}},
                            {"gain", p.gain},
                            {"gain_sigma", p.gain_sigma},
                            {"in_frame", p.in_frame},
                            {"missing", p.missing}});
    }
    j["pinholes"] = pinholes;
    j["pinholes_in_frame"] = in_frame;
    j["missing_pinholes"] = cells_json(s.missing);
    j["missing_rule"] = {{"false_alarm", 0.5 * std::erfc(f.missing_z / std::sqrt(2.0))},
                         {"z", f.missing_z},
                         {"rule", "gain + z sigma < median gain / 2"}};
    j["median_gain"] = f.median_gain;
    Json extra = Json::array();
    for (const auto& e : s.extra_spots) extra.push_back({e[0], e[1]});
    j["extra_spots"] = extra;
    j["saturated_spots"] = s.saturated_spots.size();
    j["saturated_plateau"] =
        s.plateau.found ? Json{{"pixels", s.plateau.pixels}, {"level", s.plateau.level}} : Json();
    j["background"] = s.background;
    j["background_sigma"] = s.background_sigma;
    j["optical_density"] = std::isfinite(s.optical_density) ? Json(s.optical_density) : Json();
    j["optical_density_sigma"] = s.optical_density_sigma;
    j["optical_density_is_lower_bound"] = s.optical_density_is_bound;
    j["dark_level"] = std::isfinite(s.dark_level) ? Json(s.dark_level) : Json();
    j["dark_source"] = s.dark_source;
    j["band"] = s.band;
    j["noise_sigma"] = s.noise_sigma;
    j["noise_model"] = {{"alpha", f.noise_alpha}, {"beta", f.noise_beta}};
    j["chi2_reduced"] = f.chi2_reduced;
    j["unexplained_fraction"] = f.unexplained;
    j["fit_iterations"] = f.iterations;
    j["fit_converged"] = f.converged;
    Json fit = Json::object(), unavailable = Json::object();
    for (const auto& m : s.kernel_fit) {
        if (m.available)
            fit[m.model] = m.residual;
        else
            unavailable[m.model] = m.reason;
    }
    j["kernel_fit"] = fit;
    j["kernel_models_unavailable"] = unavailable;
    j["kernel_best_model"] = s.best_model;
    j["psf"] = (dir / "psf.tiff").string();
    j["psf_period"] = s.psfs.period ? Json((dir / "psf-period.tiff").string()) : Json();
    j["psf_period_note"] = s.psfs.period_reason;
    j["kernel"] = (dir / "kernel.tiff").string();
    j["mask"] = (dir / "calibrated.mask.json").string();
    j["report"] = (dir / "report.pdf").string();
    return j;
}

void write_calibration_files(const CalibrateReport& report, const fs::path& dir, const Json& config,
                             const std::string& mask_file, const std::string& title) {
    const calibrate::CalibrationSummary& s = report.summary;
    fs::path stage = dir;
    stage += ".tmp-calibrate";
    fs::remove_all(stage);
    fs::create_directory(stage);
    try {
        PsfSidecar side = psf_sidecar_for(report.calibrated, report.kernel, mask_file);
        PsfSidecar full = side;
        full.geometry = "full-frame";
        write_psf_files(stage / "psf.tiff", s.psfs.full_frame, full, false);
        if (s.psfs.period) write_psf_files(stage / "psf-period.tiff", *s.psfs.period, side, false);
        write_image(stage / "kernel.tiff", Image(s.kernel.values));
        write_mask_file(stage / "calibrated.mask.json", report.calibrated);
        write_bytes_atomic(stage / "report.pdf",
                           calibrate::calibration_report_pdf(report.corrected, s, title));
        const Json file{{"format", "pinmask-calibration"},
                        {"version", 1},
                        {"config", config},
                        {"result", calibration_result_json(s, dir)}};
        write_bytes_atomic(stage / "calibration.json", file.dump(2) + "\n");
        if (fs::exists(dir)) fs::remove(dir);
        fs::rename(stage, dir);
    } catch (...) {
        fs::remove_all(stage);
        throw;
    }
}

}  // namespace pinmask::io
