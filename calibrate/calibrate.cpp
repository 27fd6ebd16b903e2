#include "calibrate/calibrate.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "core/field_names.hpp"
#include "core/number_format.hpp"
#include "core/resource_limits.hpp"

namespace pinmask::calibrate {

namespace {

void check_range(const char* field, double v, double lo, double hi, const char* rule) {
    if (!(v >= lo && v <= hi)) throw invalid_field(field, format_number(v), rule);
}

constexpr double kDeg = 180.0 / std::numbers::pi;
// Pixels outside the mask's footprint needed to measure the dark level there.
constexpr int kMinDarkPixels = 1000;
// Half-width of the kernel window, in cells: wide enough for the diffraction tails of a Fresnel
// kernel (N ~ 1) whose neighbours, 2 cells away at the closest, the per-pixel median rejects.
constexpr double kKernelHalfCells = 2.0;

struct Pass {
    std::vector<Spot> spots;
    LatticeFit fit;
    PinholeMatch match;
};

Pass register_spots(const Plane& frame, const Plane& raw, const Background& bg, const Mask& mask,
                    const CalibrationOptions& o) {
    Pass p;
    SpotOptions so;
    so.raw = &raw;
    so.threshold_sigmas = o.threshold_sigmas;
    so.saturation_level = o.saturation_level;
    p.spots = detect_spots(frame, bg, so);
    const int design_spots = static_cast<int>(mask.pattern.pinholes.size());
    if (p.spots.empty())
        throw InvalidInput("calibrate: no spots found in the capture (threshold " +
                           format_number(o.threshold_sigmas) + " noise sigmas above the median " +
                           format_number(bg.level) + "): is it a point-source capture?");
    if (p.spots.size() < std::max<std::size_t>(3, std::lround(o.min_spot_fraction * design_spots)))
        throw InvalidInput(
            "calibrate: far fewer spots than the design: " + std::to_string(p.spots.size()) +
            " found, the mask has " + std::to_string(design_spots) + " pinholes per period");
    int saturated = 0;
    for (const Spot& s : p.spots) saturated += s.saturated ? 1 : 0;
    const double frac = double(saturated) / double(p.spots.size());
    if (frac > o.max_saturated_fraction)
        throw InvalidInput("calibrate: saturation over most spots: " + std::to_string(saturated) +
                           " of " + std::to_string(p.spots.size()) + " spots (" +
                           format_number(std::round(1000 * frac) / 10) +
                           " %) reach the saturation level " + format_number(o.saturation_level) +
                           "; expose shorter");
    std::vector<Eigen::Vector2d> pts;
    for (const Spot& s : p.spots) pts.emplace_back(s.x, s.y);
    RegistrationOptions ro;
    ro.nominal_pitch_px = double(mask.psf.pixels_per_cell) / o.pixel_binning;
    ro.pitch_range = o.pitch_range;
    ro.max_rotation_deg = o.max_rotation_deg;
    ro.max_index_offset = o.max_index_offset;
    p.fit = fit_lattice(pts, ro);
    const double rot = p.fit.rotation_rad * kDeg;
    if (std::abs(rot) > o.max_rotation_deg)
        throw InvalidInput("calibrate: the rotation " + format_number(rot) +
                           " deg is beyond what the search covers (" +
                           field_ref("max_rotation_deg") + " " +
                           format_number(o.max_rotation_deg) + " deg)");
    p.match = match_pinholes(p.spots, p.fit, mask.pattern, static_cast<int>(frame.rows()),
                             static_cast<int>(frame.cols()), o.max_index_offset);
    int expected = 0, seen = 0;
    for (const auto& r : p.match.pinholes) {
        ++expected;
        seen += r.state != PinholeState::kMissing ? 1 : 0;
    }
    if (expected == 0 || seen < o.min_spot_fraction * expected)
        throw InvalidInput("calibrate: far fewer spots than the design: " + std::to_string(seen) +
                           " spots on the " + std::to_string(expected) +
                           " design pinholes inside the frame (the rotation may exceed " +
                           field_ref("max_rotation_deg") +
                           ", or the capture is not of this mask)");
    return p;
}

}  // namespace

void validate(const CalibrationOptions& o) {
    check_range("max_rotation_deg", o.max_rotation_deg, 0.0, 45.0, "must be in [0, 45] degrees");
    check_range("pitch_range", o.pitch_range, 0.0, 0.3, "must be in [0, 0.3]");
    check_range("threshold_sigmas", o.threshold_sigmas, 1.0, 1e6, "must be in [1, 1e6]");
    if (std::isnan(o.saturation_level) || o.saturation_level <= 0)
        throw invalid_field("saturation_level", format_number(o.saturation_level),
                            "must be > 0 (or inf)");
    check_range("max_saturated_fraction", o.max_saturated_fraction, 0.0, 1.0, "must be in [0, 1]");
    check_range("min_spot_fraction", o.min_spot_fraction, 0.0, 1.0, "must be in [0, 1]");
    check_range("period_tolerance_px", o.period_tolerance_px, 0.0, 1e3, "must be in [0, 1000]");
    check_range("max_index_offset", o.max_index_offset, 0.05, 0.45, "must be in [0.05, 0.45]");
    check_range("pixel_binning", o.pixel_binning, 1, 16, "must be in [1, 16]");
}

CalibrationSummary calibrate_point_source(const Plane& capture, const std::optional<Plane>& dark,
                                          const Mask& mask, const CalibrationOptions& o) {
    validate(o);
    if (capture.size() == 0 || !is_all_finite(capture))
        throw InvalidInput("calibrate: the capture is empty or holds NaN/Inf");
    const int rows = static_cast<int>(capture.rows()), cols = static_cast<int>(capture.cols());
    const double design_pitch = double(mask.psf.pixels_per_cell) / o.pixel_binning;
    const double period_px = mask.pattern.n * design_pitch * (1.0 - o.pitch_range);
    if (rows < period_px || cols < period_px)
        throw InvalidInput("calibrate: the capture (" + std::to_string(cols) + " x " +
                           std::to_string(rows) + " px) is smaller than one period (" +
                           format_number(mask.pattern.n * design_pitch) + " px)");
    // Working copies: frame, smoothing, masks, a few PSF-sized planes.
    check_memory(8.0 * double(rows) * cols * sizeof(double), "calibrating the capture");
    CalibrationSummary s;
    Plane frame = capture;
    if (dark) {
        if (dark->rows() != rows || dark->cols() != cols || !is_all_finite(*dark))
            throw InvalidInput("calibrate: the dark frame must be finite and the capture's size " +
                               std::to_string(cols) + " x " + std::to_string(rows));
        frame -= *dark;
        s.dark_level = dark->mean();
        s.dark_source = "dark frame";
    }
    const Background bg0 = estimate_background(frame);
    Pass pass = register_spots(frame, capture, bg0, mask, o);

    // Footprint of the mask: pixels whose nearest lattice site is a mask cell; "between spots"
    // excludes cells next to (or on) an open cell.
    const int n = mask.pattern.n;
    const int mr = n * mask.pattern.tiles_rows, mc = n * mask.pattern.tiles_cols;
    std::vector<std::uint8_t> open(static_cast<std::size_t>(n) * n, 0);
    for (const Cell& c : mask.pattern.pinholes)
        open[static_cast<std::size_t>(c.row) * n + c.col] = 1;
    auto open_at = [&](int r, int c) {
        r = ((r % n) + n) % n;
        c = ((c % n) + n) % n;
        return open[static_cast<std::size_t>(r) * n + c] != 0;
    };
    std::vector<double> between, outside;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const Eigen::Vector2d u = pass.fit.indices(c, r);
            const int R = static_cast<int>(std::lround(u.y())) + pass.match.offset_row;
            const int C = static_cast<int>(std::lround(u.x())) + pass.match.offset_col;
            if (R < -1 || C < -1 || R > mr || C > mc) {
                outside.push_back(frame(r, c));
                continue;
            }
            if (R < 0 || C < 0 || R >= mr || C >= mc) continue;  // the footprint's rim
            bool near = false;
            for (int dr = -1; dr <= 1 && !near; ++dr)
                for (int dc = -1; dc <= 1 && !near; ++dc) near = open_at(R + dr, C + dc);
            if (!near) between.push_back(frame(r, c));
        }
    double floor_level = 0.0;  // level outside the footprint (after the dark frame, if any)
    if (static_cast<int>(outside.size()) >= kMinDarkPixels) {
        floor_level = median_of(outside);
        if (!dark) {
            s.dark_level = floor_level;
            s.dark_source = "outside the mask's footprint";
        }
    } else if (!dark) {
        s.dark_source =
            "not measured (the mask's footprint fills the frame; give " + field_ref("dark") + ")";
    }
    const double inside_level = between.empty() ? bg0.level : median_of(between);
    s.background = inside_level - floor_level;

    // Second pass above the local background.
    Background bg1 = bg0;
    bg1.level = inside_level;
    pass = register_spots(frame, capture, bg1, mask, o);
    s.noise_sigma = bg0.sigma;
    s.spots = pass.spots;
    s.fit = pass.fit;
    s.match = pass.match;
    s.rotation_deg = s.fit.rotation_rad * kDeg;
    s.rotation_sigma_deg = s.fit.rotation_sigma_rad * kDeg;
    s.pitch_x_px = s.fit.pitch_x_px;
    s.pitch_y_px = s.fit.pitch_y_px;
    s.pitch_x_sigma_px = s.fit.pitch_x_sigma_px;
    s.pitch_y_sigma_px = s.fit.pitch_y_sigma_px;
    for (int k = 0; k < static_cast<int>(s.spots.size()); ++k)
        if (s.spots[k].saturated) s.saturated_spots.push_back(k);
    for (const auto& r : s.match.pinholes) {
        if (r.state == PinholeState::kMissing) s.missing.push_back(r.mask_cell);
        if (r.state == PinholeState::kMerged) s.merged.push_back(r.mask_cell);
        if (r.oversized) s.oversized.push_back(r.mask_cell);
    }
    // Position of pattern cell (0, 0) in the first tile lying wholly in the frame (else the first
    // whose cell (0, 0) does).
    auto site = [&](int R, int C) {
        return s.fit.position(C - s.match.offset_col, R - s.match.offset_row);
    };
    auto inside = [&](const Eigen::Vector2d& p) {
        return p.x() >= 0 && p.y() >= 0 && p.x() <= cols - 1 && p.y() <= rows - 1;
    };
    bool chosen = false;
    for (int pass_kind = 0; pass_kind < 2 && !chosen; ++pass_kind)
        for (int t = 0; t < mask.pattern.tiles_rows * mask.pattern.tiles_cols && !chosen; ++t) {
            const int R = n * (t / mask.pattern.tiles_cols), C = n * (t % mask.pattern.tiles_cols);
            const bool ok = pass_kind == 0
                                ? inside(site(R, C)) && inside(site(R + n - 1, C + n - 1)) &&
                                      inside(site(R, C + n - 1)) && inside(site(R + n - 1, C))
                                : inside(site(R, C));
            if (!ok) continue;
            s.first_tile = {t / mask.pattern.tiles_cols, t % mask.pattern.tiles_cols};
            const Eigen::Vector2d p = site(R, C);
            s.position_x_px = p.x();
            s.position_y_px = p.y();
            chosen = true;
        }
    if (!chosen) {
        const Eigen::Vector2d p = site(0, 0);
        s.position_x_px = p.x();
        s.position_y_px = p.y();
    }
    s.position_sigma_px = std::hypot(s.fit.x0_sigma, s.fit.y0_sigma);

    // Kernel from the good spots, above the local background.
    Plane clean = frame - inside_level;
    std::vector<Eigen::Vector2d> centres;
    std::vector<double> fluxes;
    for (const auto& r : s.match.pinholes)
        if (r.state == PinholeState::kFound && !r.oversized && !s.spots[r.spot].saturated &&
            s.spots[r.spot].flux > 0) {
            centres.push_back(r.measured);
            fluxes.push_back(s.spots[r.spot].flux);
        }
    const double pitch = 0.5 * (s.pitch_x_px + s.pitch_y_px);
    s.kernel = estimate_kernel(clean, centres, fluxes,
                               static_cast<int>(std::lround(kKernelHalfCells * pitch)));
    s.kernel_fit = compare_kernel_models(s.kernel.values, mask.camera,
                                         std::max(1, static_cast<int>(std::lround(design_pitch))));
    s.best_model = best_model(s.kernel_fit);
    // Optical density: leak per cell area against a pinhole's flux.
    const double open_flux = s.match.median_flux;
    const double leak_per_cell = s.background * s.pitch_x_px * s.pitch_y_px;
    if (leak_per_cell > 0 && open_flux > 0)
        s.optical_density = -std::log10(leak_per_cell / open_flux);
    s.psfs = calibrated_psfs(rows, cols, s.kernel, s.spots, s.match, s.fit, mask.pattern,
                             o.period_tolerance_px);
    double total = 0.0;
    for (const auto& r : s.match.pinholes)
        if (r.state == PinholeState::kFound) total += s.spots[r.spot].flux;
    std::vector<std::uint8_t> merged_done(s.spots.size(), 0);
    for (const auto& r : s.match.pinholes)
        if (r.state == PinholeState::kMerged && !merged_done[r.spot]) {
            merged_done[r.spot] = 1;
            total += s.spots[r.spot].flux;
        }
    for (int k : s.match.extra_spots) total += std::max(0.0, s.spots[k].flux);
    s.residual_map = clean - total * s.psfs.full_frame;
    return s;
}

}  // namespace pinmask::calibrate
