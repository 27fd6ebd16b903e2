// The `pinmask design` report rendered as a table (quantity, value, note); the JSON is
// io/design_json's.
#include "cli/outputs/design_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "core/units/units.hpp"
#include "design/optics/image_plane.hpp"
#include "design/optics/spectrum.hpp"

namespace pinmask::cli {
namespace {

std::string num(double v, int digits = 4) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string length(double v) { return format_length(v); }

// Micrometres to the nanometre's thousandth: a pinhole side and its value on the grid differ
// below format_length's four digits.
std::string fine_length(double v) {
    if (!std::isfinite(v)) return length(v);
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6f um", v * 1e6);
    return buf;
}

std::string range_text(const WorkingDistance& wd) {
    return length(wd.range_near_m) + (wd.range_near_clamped_to_focal ? " (f')" : "") + " .. " +
           length(wd.range_far_m);
}

// "850 nm, one wavelength" or "850 nm +- 30 nm FWHM: 13 samples 805 nm .. 895 nm".
std::string spectrum_text(const Camera& c) {
    const auto wl = band_wavelengths(c);
    if (wl.size() == 1) return length(c.wavelength_m) + ", one wavelength";
    return length(c.wavelength_m) + ", FWHM " + length(c.bandwidth_m) + ": " +
           std::to_string(wl.size()) + " samples " + length(wl.front().first) + " .. " +
           length(wl.back().first);
}

std::string kernel_support_text(const DesignKernel& dk) {
    if (!dk.kernel) return "not built";
    const Kernel& k = *dk.kernel;
    return std::to_string(k.values.rows()) + " x " + std::to_string(k.values.cols()) + " px, " +
           num(100.0 * k.enclosed_energy, 4) + " % of the energy" +
           (k.support_capped ? " (capped at the period)" : "");
}

std::string regime_text(const OpticsReport& r, const WorkingDistance& wd) {
    std::string s = kernel_model_name(r.kernel_model) +
                    ", N_F = " + num(wd.fresnel_number_with_lens_at_u, 3) + "; spot ~" +
                    num(wd.spot_spread_cells, 3) + " cells";
    if (wd.spreads_beyond_cell()) s += "  WARNING: spots spread over more than one cell";
    return s;
}

}  // namespace

std::string design_table(const OpticsReport& r, const WorkingDistance& wd,
                         const std::string& solved, const std::vector<CameraInput>& inputs,
                         const GridSnap& snap, const DesignKernel& dk) {
    const Camera& c = r.camera;
    const std::string at_u_text = "u = " + length(c.object_distance_m);
    const std::string inf = "  u = inf";  // the distant-object line under a figure at u
    std::vector<std::vector<std::string>> rows = {
        {"WORKING DISTANCE", "",
         at_u_text + ": every figure is at u; the \"u = inf\" lines below "
                     "them are the distant-object values the paper quotes"},
        {"magnification M(u)", num(r.magnification_at_u), "1 - f/f' + f/u (< 0 past focus)"},
        {inf, num(r.magnification), "1 - f/f'"},
        {"geometric spot = cell pitch p(u)", length(r.geometric_spot_at_u_m), "d |M(u)|"},
        {inf, length(r.geometric_spot_m), "d |1 - f/f'|"},
        {"pixels per cell (pitch at u)", num(r.pixels_per_cell_at_u, 8), "p(u) / w"},
        {inf, num(r.pixels_per_cell_at_inf), "p / w at u = inf"},
        {"whole pixels per cell N at u", std::to_string(wd.pixels_per_cell),
         solved.empty() ? "nearest whole number to the pitch at u" : solved},
        {inf, std::to_string(r.integer_pixels_per_cell), "nearest whole number at u = inf"},
        {"pinhole for N px per cell at u", fine_length(wd.pinhole_for_pixels_per_cell_m),
         "N w / |1 - f/f' + f/u|" + std::string(solved.empty() ? "" : " (before the grid)")},
        {inf, length(r.pinhole_for_integer_pixels_m), "n_px w / |1 - f/f'|"},
    };
    if (snap.solved) {
        char shift[160];
        std::snprintf(shift, sizeof shift, "%+.3g px per cell, %+.3g px across one period",
                      snap.pitch_shift_px, snap.pitch_shift_px * r.geometry.n);
        rows.push_back({"pinhole on the fabrication grid", fine_length(snap.on_grid_m),
                        "d snapped to the " + std::to_string(snap.grid_nm) + " nm grid (" +
                            snap.grid_source + "): used above"});
        rows.push_back({"  pitch at u moved by the grid", shift,
                        "pitch(u) of the grid d minus N (what export draws)"});
    }
    const std::vector<std::vector<std::string>> rest = {
        {"period at u", num(wd.period_px, 8) + " px", "n d |M(u)| / w"},
        {"PSF size (one period)",
         std::to_string(wd.psf_size_px) + " x " + std::to_string(wd.psf_size_px) + " px",
         "n N (the decoder's torus at u)"},
        {inf, std::to_string(r.psf_size_px) + " x " + std::to_string(r.psf_size_px) + " px",
         "n n_px at u = inf"},
        {"periods on the sensor",
         num(wd.periods_on_sensor_cols, 3) + " x " + num(wd.periods_on_sensor_rows, 3),
         std::to_string(c.sensor_cols) + " x " + std::to_string(c.sensor_rows) + " px / (n N)"},
        {inf, num(r.periods_on_sensor_cols, 3) + " x " + num(r.periods_on_sensor_rows, 3),
         "sensor / (n n_px) at u = inf"},
        {"LSI mismatch at u", num(wd.lsi_mismatch_px, 3) + " px",
         "n |pitch(u) - N| against the N-pixel model the decoder uses: " +
             std::string(wd.is_shift_invariant() ? "shift invariant" : "NOT shift invariant") +
             " within " + num(r.options.lsi_tolerance_px) + " px"},
        {"  against the u = inf pitch", num(r.lsi_mismatch_px) + " px",
         "f s_max / (u w): how far u is from the distant-object design"},
        {"  LSI min object distance", length(r.lsi_min_object_distance_m),
         "f s_max / (" + num(r.options.lsi_tolerance_px) +
             " px * w): where the u = inf design holds"},
        {"usable object distances", range_text(wd),
         "pitch within " + num(r.options.lsi_tolerance_px) +
             " px of u's across s_max: f s_max |1/u' - 1/u| / w"},
        {"image distance v at u", length(image_distance_at_u_m(c)),
         "1/v = 1/f' - 1/u (Eq. (2)): a lens camera's sensor plane; this one sits at f"},
        {"diffraction first zero", num(diffraction_first_zero_px(c), 3) + " px",
         "lambda f / (d w): centre to first zero of one pinhole's sinc^2 spot, at any u"},
        {"largest separation s_max", length(r.max_separation_m), "n d"},
        {"effective distance z_eff(u)", length(r.effective_distance_at_u_m),
         "1/z = 1/f - 1/f' + 1/u"},
        {inf, length(r.effective_distance_m), "f f' / (f' - f) (inf: f = f'; < 0: past focus)"},
        {"Fresnel number with lens at u", num(r.fresnel_number_with_lens_at_u),
         "d^2 / (4 lambda |z_eff(u)|): used by the kernel models"},
        {inf, num(r.fresnel_number_with_lens), "d^2 / (4 lambda |z_eff|)"},
        {"Fresnel number, no lens", num(r.fresnel_number), "d^2 / (4 lambda f)"},
        {"optimum pinhole, lensless", length(wd.optimum_pinhole_lensless_m),
         "1.56 sqrt(lambda f) (the paper's rule)"},
        {"optimum pinhole, with the lens", length(wd.optimum_pinhole_with_lens_m),
         "1.56 sqrt(lambda |z_eff(u)|), z_eff(u) = 1/(1/f - 1/f' + 1/u)"},
        {"regime", regime_text(r, wd),
         "Fresnel number with the lens at u; spot = max(1, 1/(2 N_F)) cells"},
        {"kernel model", kernel_model_name(r.kernel_model), r.kernel_reason},
        {"spectrum", spectrum_text(c),
         c.bandwidth_m == 0.0 ? "--bandwidth 0: the design wavelength alone"
                              : "Gaussian band of that FWHM, 13 wavelengths over +-1.5 FWHM"},
        {"kernel support", kernel_support_text(dk),
         dk.kernel ? "what psf builds at N px per cell over the band (psf --energy)"
                   : dk.not_built},
        {"mask size", length(r.mask_width_m) + " x " + length(r.mask_height_m),
         "n tiles d per side"},
        {"open fraction", num(100 * r.open_fraction, 3) + " %", "K / n^2"},
        {"light gain", num(r.light_gain) + " x", "K: light over one pinhole"},
    };
    rows.insert(rows.end(), rest.begin(), rest.end());
    std::size_t w0 = 8, w1 = 5;
    for (const auto& row : rows) {
        w0 = std::max(w0, row[0].size());
        w1 = std::max(w1, row[1].size());
    }
    std::ostringstream s;
    auto line = [&](const std::string& a, const std::string& b, const std::string& n) {
        s << a << std::string(w0 + 2 - a.size(), ' ') << b << std::string(w1 + 2 - b.size(), ' ')
          << n << "\n";
    };
    line("input", "value", "from");
    for (const CameraInput& in : inputs) line(in.symbol, in.value, in.source);
    s << "\n";
    line("quantity", "value", "note");
    for (const auto& row : rows) line(row[0], row[1], row[2]);
    return s.str();
}

}  // namespace pinmask::cli
