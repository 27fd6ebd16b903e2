#include "decode/calibrate/calibrate.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "decode/calibrate/profile_table.hpp"
#include "design/optics/optics.hpp"

namespace pinmask::calibrate {

namespace {

void check_range(const std::string& field, double v, double lo, double hi, const char* rule) {
    if (!(v >= lo && v <= hi)) throw invalid_field(field, format_number(v), rule);
}

constexpr double kDeg = 180.0 / std::numbers::pi;
// Half-width of the window the fitted kernel is written on, in cells.
constexpr double kKernelHalfCells = 2.0;
// Trust: the median pinhole's flux in standard errors, and the residual's share of the signal.
constexpr double kMinGainSnr = 10.0;
constexpr double kMaxUnexplained = 0.05;
constexpr double kExtraFluxFraction = 0.25;

// Whether the point source's spots stand apart: each spot's main lobe ends within one cell
// pitch of its centre (box: half the geometric spot; fraunhofer and fresnel: v = 2 N + 1, the
// Fresnel pattern's geometric half width and the sinc's first zero). A pinhole small against
// its cell (the walkthrough's 120 um on 9 px cells: a lobe of +-59 px) images every pinhole
// into one blob, whose spot count says nothing about the pinholes.
bool spots_stand_apart(const Mask& mask) {
    const Camera& c = mask.camera;
    const KernelModel family =
        fit_family(c, parse_kernel_model(mask.psf.kernel.model, "kernel model"));
    if (family == KernelModel::kBox)
        return 0.5 * std::abs(magnification_at_u(c)) * c.pinhole_m / c.pixel_pitch_m <
               mask.psf.pixels_per_cell;
    const double a = c.pinhole_m * c.pixel_pitch_m / (c.wavelength_m * c.sensor_distance_m);
    const double n = family == KernelModel::kFresnel ? fresnel_number_at_u(c) : 0.0;
    return (2.0 * n + 1.0) / a < mask.psf.pixels_per_cell;
}

// How a plateau found in the capture is named in messages.
std::string plateau_words(const SaturatedPlateau& p) {
    return " (no " + field_ref("saturation_level") + " given: the capture's largest value, where " +
           std::to_string(p.pixels) + " pixels form a flat top of clipped light)";
}

// The spots above the threshold: refusals of captures that are not a usable point source (no
// spots, far fewer than the design, saturated). The lattice itself starts from the FFT
// (decode/calibrate/lattice_fft), not from these spots.
std::vector<Spot> checked_spots(const Plane& frame, const Plane& raw, const Background& bg,
                                const Mask& mask, const CalibrationOptions& o,
                                const SaturatedPlateau& plateau) {
    SpotOptions so;
    so.raw = &raw;
    so.threshold_sigmas = o.threshold_sigmas;
    so.saturation_level = o.saturation_level;
    std::vector<Spot> spots = detect_spots(frame, bg, so);
    const int design_spots = static_cast<int>(mask.pattern.pinholes.size());
    // Spots that run together into one blob are counted by nothing here: the fit's own refusals
    // (too few photons, a capture the model does not explain) judge such a capture.
    const bool apart = spots_stand_apart(mask);
    if (!apart && spots.empty()) return spots;
    if (spots.empty())
        throw InvalidInput("calibrate: no spots found in the capture (threshold " +
                           format_number(o.threshold_sigmas) + " noise sigmas above the median " +
                           format_number(bg.level) + "): is it a point-source capture?");
    if (apart &&
        spots.size() < std::max<std::size_t>(3, std::lround(o.min_spot_fraction * design_spots)))
        throw InvalidInput(
            "calibrate: far fewer spots than the design: " + std::to_string(spots.size()) +
            " found, the mask has " + std::to_string(design_spots) + " pinholes per period");
    int saturated = 0;
    for (const Spot& s : spots) saturated += s.saturated ? 1 : 0;
    const double frac = double(saturated) / double(spots.size());
    if (frac > o.max_saturated_fraction)
        throw InvalidInput("calibrate: saturation over most spots: " + std::to_string(saturated) +
                           " of " + std::to_string(spots.size()) + " spots (" +
                           format_number(std::round(1000 * frac) / 10) +
                           " %) reach the saturation level " + format_number(o.saturation_level) +
                           (plateau.found ? plateau_words(plateau) : std::string()) +
                           "; expose shorter");
    return spots;
}

// The fit cannot be trusted: too few photons (the median pinhole's flux below kMinGainSnr of its
// standard error) or a capture the model does not explain (more than kMaxUnexplained of the
// signal's energy left in the residual beyond the noise model's variance).
void check_trust(const ForwardFit& f, const CalibrationOptions&) {
    std::vector<double> sig;
    for (const auto& p : f.pinholes)
        if (p.in_frame) sig.push_back(p.gain_sigma);
    const double gs = median_of(sig);
    // A non-positive median flux is a fit that did not find the lattice, not a dim capture.
    if (!(f.median_gain > 0))
        throw InvalidInput(
            "calibrate: the fit did not find the mask's lattice in the capture (the "
            "median pinhole flux came out " +
            format_number(f.median_gain) + "): is it a capture of this mask, rotated within " +
            field_ref("max_rotation_deg") + "?");
    if (!(f.median_gain > kMinGainSnr * gs))
        throw InvalidInput(
            "calibrate: too few photons to trust the fit: the median pinhole's flux " +
            format_number(f.median_gain) + " is " +
            format_number(gs > 0 ? f.median_gain / gs : 0.0) + " standard errors (at least " +
            format_number(kMinGainSnr) + " needed); expose longer or average captures");
    if (f.chi2_reduced > 1.0 && f.unexplained > kMaxUnexplained)
        throw InvalidInput(
            "calibrate: the capture is not explained by this mask's point-source model: " +
            format_number(std::round(1000 * f.unexplained) / 10) +
            " % of its signal remains in the residual (at most " +
            format_number(100 * kMaxUnexplained) +
            " % allowed); is it a point-source capture through this mask?");
}

// Extra light: blobs of the residual normalised by the noise model's sigma (decode/calibrate/spots
// on it) whose residual flux reaches kExtraFluxFraction of the median pinhole flux.
std::vector<std::array<double, 3>> extra_light(const Plane& residual, const ForwardFit& f,
                                               const CalibrationOptions& o) {
    const Plane z = residual / (f.noise_alpha * f.model.max(0.0) + f.noise_beta).sqrt();
    SpotOptions so;
    so.threshold_sigmas = o.threshold_sigmas;
    so.relative_threshold = 0.0;
    std::vector<std::array<double, 3>> out;
    for (const Spot& sp : detect_spots(z, Background{0.0, 1.0}, so)) {
        double flux = 0.0;
        for (int r = sp.row0; r <= sp.row1; ++r)
            for (int c = sp.col0; c <= sp.col1; ++c) flux += residual(r, c);
        if (flux >= kExtraFluxFraction * f.median_gain) out.push_back({sp.x, sp.y, flux});
    }
    return out;
}

// The fit's kernel is one wavelength's (decode/calibrate/profile_table: separable, which a band's
// sum over wavelengths is not): a band is fitted at its centre, where its blur of the kernel's
// fringes goes into the fitted side (docs/calibration.md measures what that costs).
std::string band_treatment(const Camera& c) {
    if (!(c.bandwidth_m > 0)) return "one wavelength, " + format_length(c.wavelength_m);
    return "fitted at the band's centre " + format_length(c.wavelength_m) + " (the band's FWHM " +
           format_length(c.bandwidth_m) +
           " is not modelled: its blur of the kernel's fringes enters the fitted pinhole side)";
}

}  // namespace

void validate(const CalibrationOptions& o) {
    check_range(field_ref("max_rotation_deg"), o.max_rotation_deg, 0.0, 45.0,
                "must be in [0, 45] degrees");
    check_range(field_ref("pitch_range"), o.pitch_range, 0.0, 0.3, "must be in [0, 0.3]");
    check_range(field_ref("threshold_sigmas"), o.threshold_sigmas, 1.0, 1e6, "must be in [1, 1e6]");
    if (std::isnan(o.saturation_level) || o.saturation_level <= 0)
        throw invalid_field(field_ref("saturation_level"), format_number(o.saturation_level),
                            "must be > 0 (or inf)");
    check_range("max_saturated_fraction", o.max_saturated_fraction, 0.0, 1.0, "must be in [0, 1]");
    check_range("min_spot_fraction", o.min_spot_fraction, 0.0, 1.0, "must be in [0, 1]");
    check_range("period_tolerance_px", o.period_tolerance_px, 0.0, 1e3, "must be in [0, 1000]");
    check_range("pixel_binning", o.pixel_binning, 1, 16, "must be in [1, 16]");
}

CalibrationSummary calibrate_point_source(const Plane& capture, const std::optional<Plane>& dark,
                                          const Mask& mask, const CalibrationOptions& given) {
    validate(given);
    if (capture.size() == 0 || !is_all_finite(capture))
        throw InvalidInput("calibrate: the capture is empty or holds NaN/Inf");
    check_capture_scale(capture);
    // No ceiling given: a flat top at the capture's largest value is its ceiling.
    CalibrationOptions o = given;
    SaturatedPlateau plateau;
    if (std::isinf(o.saturation_level) && o.detect_saturation) {
        plateau = find_saturated_plateau(capture);
        if (plateau.found) o.saturation_level = plateau.level;
    }
    const int rows = static_cast<int>(capture.rows()), cols = static_cast<int>(capture.cols());
    const double design_pitch = double(mask.psf.pixels_per_cell) / o.pixel_binning;
    const double period_px = mask.pattern.n * design_pitch * (1.0 - o.pitch_range);
    if (rows < period_px || cols < period_px)
        throw InvalidInput("calibrate: the capture (" + std::to_string(cols) + " x " +
                           std::to_string(rows) + " px) is smaller than one period (" +
                           format_number(mask.pattern.n * design_pitch) + " px)");
    // Working copies: frame, model, weights, derivative planes.
    check_memory(16.0 * double(rows) * cols * sizeof(double), "calibrating the capture");
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
    // Refusals from the spots, then the start of the lattice from the FFT.
    const Background bg0 = estimate_background(frame);
    s.spots = checked_spots(frame, capture, bg0, mask, o, plateau);
    for (int k = 0; k < static_cast<int>(s.spots.size()); ++k)
        if (s.spots[k].saturated) s.saturated_spots.push_back(k);
    if (plateau.found) {
        s.plateau = plateau;
        s.warnings.push_back(
            "the capture has " + std::to_string(plateau.pixels) + " pixels at exactly its " +
            "largest value " + format_number(plateau.level) + ", a flat top of clipped light (no " +
            field_ref("saturation_level") + " given); " + std::to_string(s.saturated_spots.size()) +
            " of " + std::to_string(s.spots.size()) +
            " spots reach it, and their centroids, gains and the kernel are biased: expose "
            "shorter (or give " +
            field_ref("saturation_level") +
            " if that value is not a "
            "ceiling)");
    }
    FftStartOptions so;
    so.nominal_pitch_px = design_pitch;
    so.pitch_range = o.pitch_range;
    so.max_rotation_deg = o.max_rotation_deg;
    const auto phase = [&](const char* name) {
        if (o.progress) o.progress(name, 0, 0);
    };
    phase("finding the lattice (FFT)");
    {
        // A capture the fit bins (decode/calibrate/forward_fit) is searched binned as well: its
        // cells are still at least 8 px wide, and b^2 times fewer pixels enter the FFTs and folds.
        const int b = first_pass_binning(design_pitch, rows, cols);
        if (b > 1) {
            so.nominal_pitch_px = design_pitch / b;
            s.fft_start = fft_lattice_start(bin_frame(frame, b), mask.pattern, so);
            s.fft_start.lattice = from_binned(s.fft_start.lattice, b);
            s.fft_start.max_frequency /= b;
        } else {
            s.fft_start = fft_lattice_start(frame, mask.pattern, so);
        }
    }
    s.band = band_treatment(mask.camera);
    const LatticeStart start = s.fft_start.lattice;
    ForwardFitOptions fo;
    fo.dark_subtracted = dark.has_value();
    phase("fitting the forward model");
    int fit_iterations = 0;  // over every round of the fit, for the progress text
    if (o.progress)
        fo.on_iteration = [&](int, int cap) {
            o.progress("fitting the forward model", ++fit_iterations, cap);
        };
    s.fit = fit_forward_model(frame, mask, start, fo);
    // Spots several cells wide run together in the spot start, which can then assign the lattice
    // one cell off; the fit of a wrong assignment ends on a negative median gain. Then the eight
    // neighbouring assignments are fitted and the one with the smallest chi^2 and a positive
    // median gain is kept.
    if (!(s.fit.median_gain > 0)) {
        const double ct = std::cos(start.rotation_rad), st = std::sin(start.rotation_rad);
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                if (di == 0 && dj == 0) continue;
                LatticeStart alt = start;
                alt.x0 -= start.pitch_x_px * ct * di + start.pitch_y_px * st * dj;
                alt.y0 -= -start.pitch_x_px * st * di + start.pitch_y_px * ct * dj;
                try {
                    ForwardFit g = fit_forward_model(frame, mask, alt, fo);
                    if (g.median_gain > 0 &&
                        (!(s.fit.median_gain > 0) || g.chi2_reduced < s.fit.chi2_reduced))
                        s.fit = std::move(g);
                } catch (const InvalidInput&) {
                }
            }
    }
    const ForwardFit& f = s.fit;
    s.design_pitch_px = design_pitch;
    s.rotation_deg = f.lattice.rotation_rad * kDeg;
    s.rotation_sigma_deg = f.rotation_sigma_rad * kDeg;
    if (std::abs(s.rotation_deg) > o.max_rotation_deg)
        throw InvalidInput("calibrate: the fitted rotation " + format_number(s.rotation_deg) +
                           " deg is beyond what the search covers (" +
                           field_ref("max_rotation_deg") + " " + format_number(o.max_rotation_deg) +
                           " deg)");
    s.pitch_x_px = f.lattice.pitch_x_px;
    s.pitch_y_px = f.lattice.pitch_y_px;
    s.pitch_x_sigma_px = f.pitch_x_sigma_px;
    s.pitch_y_sigma_px = f.pitch_y_sigma_px;
    check_trust(f, o);
    for (const auto& p : f.pinholes)
        if (p.missing) s.missing.push_back(p.mask_cell);

    // Position of pattern cell (0, 0) in the first tile lying wholly in the frame (else the first
    // whose cell (0, 0) does).
    const int n = mask.pattern.n;
    auto site = [&](int R, int C) {
        const double ct = std::cos(f.lattice.rotation_rad), st = std::sin(f.lattice.rotation_rad);
        return Eigen::Vector2d(
            f.lattice.x0 + f.lattice.pitch_x_px * ct * C + f.lattice.pitch_y_px * st * R,
            f.lattice.y0 - f.lattice.pitch_x_px * st * C + f.lattice.pitch_y_px * ct * R);
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
        s.position_x_px = f.lattice.x0;
        s.position_y_px = f.lattice.y0;
    }
    s.position_sigma_px = std::hypot(f.x0_sigma, f.y0_sigma);

    // Background and leak. Without a dark frame the fitted background is the dark level.
    s.background = f.leak;
    s.background_sigma = f.leak_sigma;
    if (!dark) {
        s.dark_level = f.background;
        s.dark_source = "fitted background";
    } else {
        s.dark_level += f.background;
    }
    s.noise_sigma = std::sqrt(f.noise_alpha * std::max(f.background, 0.0) + f.noise_beta);
    const double cell_area = s.pitch_x_px * s.pitch_y_px;
    if (!f.leak_measured) {
        s.optical_density = std::numeric_limits<double>::quiet_NaN();
        s.dark_source +=
            " (the footprint fills the frame: leak not measured; give " + field_ref("dark") + ")";
    } else if (f.median_gain > 0) {
        const double to_t = cell_area / f.median_gain;
        if (f.leak > 2 * f.leak_sigma && f.leak > 0) {
            const double t = f.leak * to_t;
            s.optical_density = std::max(0.0, -std::log10(t));
            s.optical_density_sigma = f.leak_sigma / (f.leak * std::log(10.0));
        } else if (f.leak_sigma > 0) {
            s.optical_density = std::max(0.0, -std::log10((f.leak + 2 * f.leak_sigma) * to_t));
            s.optical_density_is_bound = true;
        }
    }

    // Kernel: the fitted one, on a window of two cells either side, against the design's models.
    const double pitch = 0.5 * (s.pitch_x_px + s.pitch_y_px);
    const int half = static_cast<int>(std::lround(kKernelHalfCells * pitch));
    s.kernel.values = fitted_kernel(f, mask, half);
    s.kernel.half_px = half;
    s.kernel.spots_used = static_cast<int>(f.pinholes.size());
    s.kernel_fit = compare_kernel_models(s.kernel.values, mask.camera,
                                         std::max(1, static_cast<int>(std::lround(design_pitch))));
    s.best_model = best_model(s.kernel_fit);
    phase("building the calibrated PSF");
    s.psfs = calibrated_psfs(rows, cols, f, mask, o.period_tolerance_px);
    s.residual_map = frame - f.model;
    s.extra_spots = extra_light(s.residual_map, f, o);
    return s;
}

}  // namespace pinmask::calibrate
