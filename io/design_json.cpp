#include "io/design_json.hpp"

#include <cmath>
#include <string>

#include "design/optics/image_plane.hpp"
#include "design/optics/spectrum.hpp"

namespace pinmask::io {
namespace {

// A number, or null with a note when it is infinite.
void put(nlohmann::ordered_json& j, nlohmann::ordered_json& notes, const std::string& key, double v,
         const std::string& why_infinite = "") {
    if (std::isfinite(v)) {
        j[key] = v;
    } else {
        j[key] = nullptr;
        notes[key] = std::string(v > 0 ? "+inf" : "-inf") +
                     (why_infinite.empty() ? "" : ": " + why_infinite);
    }
}

}  // namespace

nlohmann::ordered_json design_json(const DesignReport& d) {
    using Json = nlohmann::ordered_json;
    const OpticsReport& r = d.optics;
    const WorkingDistance& wd = d.working;
    const GridSnap& snap = d.snap;
    const DesignKernel& dk = d.kernel;
    Json j, notes = Json::object();
    const Camera& c = r.camera;
    Json cam;
    put(cam, notes, "object_distance_m", c.object_distance_m, "distant object");
    put(cam, notes, "lens_focal_m", c.lens_focal_m, "no lens");
    cam["sensor_distance_m"] = c.sensor_distance_m;
    cam["wavelength_m"] = c.wavelength_m;
    cam["bandwidth_m"] = c.bandwidth_m;
    cam["pixel_pitch_m"] = c.pixel_pitch_m;
    cam["pinhole_m"] = c.pinhole_m;
    cam["sensor_px"] = {c.sensor_cols, c.sensor_rows};
    j["camera"] = cam;
    j["geometry"] = {{"n", r.geometry.n},
                     {"holes", r.geometry.holes},
                     {"tiles", {r.geometry.tiles_rows, r.geometry.tiles_cols}}};
    // Keys without a suffix are at the working distance u (as are the "_at_u" keys); "_at_inf"
    // keys are the distant-object design values the paper quotes (docs/commands.md).
    const std::string focus = "f = f' (Fraunhofer limit: 1/z_eff = 0)";
    j["optimum_pinhole_m"] = r.optimum_pinhole_m;
    j["fresnel_number"] = r.fresnel_number;
    j["fresnel_number_with_lens"] = r.fresnel_number_with_lens_at_u;
    j["fresnel_number_with_lens_at_u"] = r.fresnel_number_with_lens_at_u;
    j["fresnel_number_with_lens_at_inf"] = r.fresnel_number_with_lens;
    const std::string focus_at_u =
        "1/f - 1/f' + 1/u = 0 (e.g. f = f' at u = inf: the Fraunhofer limit)";
    put(j, notes, "effective_distance_m", r.effective_distance_at_u_m, focus_at_u);
    put(j, notes, "effective_distance_at_u_m", r.effective_distance_at_u_m, focus_at_u);
    put(j, notes, "effective_distance_at_inf_m", r.effective_distance_m, focus);
    j["magnification"] = r.magnification_at_u;
    j["magnification_at_u"] = r.magnification_at_u;
    j["magnification_at_inf"] = r.magnification;
    j["geometric_spot_m"] = r.geometric_spot_at_u_m;
    j["geometric_spot_at_u_m"] = r.geometric_spot_at_u_m;
    j["geometric_spot_at_inf_m"] = r.geometric_spot_m;
    j["pixels_per_cell"] = r.pixels_per_cell_at_u;
    j["pixels_per_cell_at_u"] = r.pixels_per_cell_at_u;
    j["pixels_per_cell_at_inf"] = r.pixels_per_cell_at_inf;
    j["integer_pixels_per_cell"] = wd.pixels_per_cell;
    j["integer_pixels_per_cell_at_inf"] = r.integer_pixels_per_cell;
    put(j, notes, "pinhole_for_integer_pixels_m", wd.pinhole_for_pixels_per_cell_m,
        "1 - f/f' + f/u = 0: every pinhole images to the same spot");
    put(j, notes, "pinhole_for_integer_pixels_at_inf_m", r.pinhole_for_integer_pixels_m,
        "magnification 1 - f/f' = 0: every pinhole images to the same spot");
    put(j, notes, "image_distance_at_u_m", image_distance_at_u_m(c),
        "no lens (f' = inf): the object at u forms no image");
    j["diffraction_first_zero_px"] = diffraction_first_zero_px(c);
    j["max_separation_m"] = r.max_separation_m;
    j["lsi_tolerance_px"] = r.options.lsi_tolerance_px;
    j["lsi_mismatch_px"] = wd.lsi_mismatch_px;
    j["lsi_shift_invariant"] = wd.is_shift_invariant();
    j["lsi_mismatch_at_inf_px"] = r.lsi_mismatch_px;
    j["lsi_min_object_distance_at_inf_m"] = r.lsi_min_object_distance_m;
    j["psf_size_px"] = wd.psf_size_px;
    j["psf_size_at_inf_px"] = r.psf_size_px;
    j["periods_on_sensor"] = {{"cols", wd.periods_on_sensor_cols},
                              {"rows", wd.periods_on_sensor_rows}};
    j["periods_on_sensor_at_inf"] = {{"cols", r.periods_on_sensor_cols},
                                     {"rows", r.periods_on_sensor_rows}};
    j["mask_size_m"] = {{"width", r.mask_width_m}, {"height", r.mask_height_m}};
    j["open_fraction"] = r.open_fraction;
    j["light_gain"] = r.light_gain;
    j["kernel_model"] = kernel_model_name(r.kernel_model);
    j["kernel_reason"] = r.kernel_reason;
    {
        // The band the kernels sum (design/optics/spectrum) and the kernel psf would build with it.
        Json wl = Json::array();
        for (const auto& [lambda, weight] : band_wavelengths(c)) wl.push_back({lambda, weight});
        j["spectrum"] = {{"bandwidth_m", c.bandwidth_m}, {"wavelengths", wl}};
        Json k;
        if (dk.kernel) {
            k["support_px"] = {dk.kernel->values.rows(), dk.kernel->values.cols()};
            k["enclosed_energy"] = dk.kernel->enclosed_energy;
            k["support_capped"] = dk.kernel->support_capped;
        } else {
            k["not_built"] = dk.not_built;
        }
        j["kernel"] = k;
    }
    j["whole_pixels_per_cell_at_u"] = wd.pixels_per_cell;
    put(j, notes, "pinhole_for_pixels_per_cell_m", wd.pinhole_for_pixels_per_cell_m,
        "1 - f/f' + f/u = 0: every pinhole images to the same spot");
    j["period_at_u_px"] = wd.period_px;
    j["lsi_mismatch_at_u_px"] = wd.lsi_mismatch_px;
    j["object_distance_range_m"] = {
        wd.range_near_m, std::isfinite(wd.range_far_m) ? Json(wd.range_far_m) : Json(nullptr)};
    if (!std::isfinite(wd.range_far_m)) {
        notes["object_distance_range_m"] = "far end +inf: shift invariant out to infinity";
    }
    j["optimum_pinhole_lensless_m"] = wd.optimum_pinhole_lensless_m;
    put(j, notes, "optimum_pinhole_with_lens_m", wd.optimum_pinhole_with_lens_m,
        "z_eff(u) infinite (f = f' at u = inf): no diffraction distance to balance; the lensless "
        "rule optimum_pinhole_lensless_m is the limit");
    put(j, notes, "spot_spread_cells", wd.spot_spread_cells, "Fresnel number 0");
    j["spot_spreads_beyond_cell"] = wd.spreads_beyond_cell();
    if (snap.solved) {
        j["fab_grid_m"] = double(snap.grid_nm) * 1e-9;
        j["pinhole_solved_m"] = snap.exact_m;
        j["pinhole_on_grid_m"] = snap.on_grid_m;
        j["grid_pitch_shift_px"] = snap.pitch_shift_px;
        j["grid_period_shift_px"] = snap.pitch_shift_px * r.geometry.n;
    }
    j["notes"] = notes;
    // The spacing rule's packing bound on the pinhole count, psf's warnings for the kernel it
    // would build, and where each camera value came from.
    j["spacing_cells"] = d.spacing_cells;
    j["max_holes_at_spacing"] = d.packing.count;
    j["max_holes_reason"] = d.packing.reason;
    j["kernel_warnings"] = dk.validity.warnings;
    Json sources = Json::object();
    for (const auto& [symbol, source] : d.input_sources) sources[symbol] = source;
    j["input_sources"] = sources;
    return j;
}

}  // namespace pinmask::io
