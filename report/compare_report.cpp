#include "report/compare_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/units/units.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"

namespace pinmask {
namespace {

// "inf", "n/a" (NaN) or printf with the given format.
// The simulated scenes' names, comma-separated.
std::string scene_list(const MaskMetricsOptions& mo) {
    std::string out;
    for (const SceneSpec& s : mo.scenes) out += (out.empty() ? "" : ", ") + scene_name(s);
    return out;
}

std::string fmt(double v, const char* format) {
    if (std::isnan(v)) return "n/a";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[48];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}
std::string db(double v) { return fmt(v, "%.2f"); }
std::string ratio(double v) { return fmt(v, "%.3g"); }
std::string ssim_text(double v) { return fmt(v, "%.3f"); }

// A difference to the first mask: "+0.146 exact", "-0.31 +- 0.22" with " n.s." under two
// standard errors, "+0.31 (1 scene)" without a spread.
std::string difference_text(const PairedDifference& d) {
    const std::string v = fmt(d.difference, "%+.3f");
    if (d.exact) return v + " exact";
    if (!std::isfinite(d.standard_error)) return v + " (1 scene)";
    return v + " +- " + fmt(d.standard_error, "%.3f") + (d.significant ? "" : " n.s.");
}

std::string px(int rows, int cols) { return std::to_string(rows) + " x " + std::to_string(cols); }

// Display range of a picture: [min, max] of its finite values, widened when flat.
std::pair<double, double> finite_range(const Plane& p) {
    double lo = INFINITY, hi = -INFINITY;
    for (Eigen::Index i = 0; i < p.size(); ++i) {
        const double v = p.data()[i];
        if (!std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    if (!(lo < hi)) {
        lo = std::isfinite(lo) ? lo - 0.5 : 0.0;
        hi = lo + 1.0;
    }
    return {lo, hi};
}

ReportPanel panel(std::string caption, const Plane& values, double lo, double hi, std::string scale,
                  std::vector<std::string> notes = {}) {
    ReportPanel p;
    p.caption = std::move(caption);
    p.values = values;
    p.lo = lo;
    p.hi = hi;
    p.scale = std::move(scale);
    p.notes = std::move(notes);
    return p;
}

std::string zero_text(const CompareRow& r) {
    const SpectralZero& z = *r.metrics.spectral_zero;
    if (!z.found) return "none";
    return "(" + std::to_string(z.row) + "," + std::to_string(z.col) + ")";
}

std::string spacing_text(const CompareRow& r) {
    std::ostringstream s;
    s << "spacing >= " << r.min_spacing_cells << " cells on the torus: ";
    if (r.spacing_ok) {
        s << "met";
    } else {
        s << r.spacing_violations << " pair(s) closer - breaks the rule";
    }
    return s.str();
}

ReportMaskPage mask_page(const CompareResult& res, std::size_t index, const Camera& camera,
                         const CompareSettings& s) {
    const CompareRow& r = res.row;
    const ComparePictures& p = res.pictures;
    const int n = r.n, m = r.period_px;
    ReportMaskPage page;
    page.title =
        std::to_string(index + 1) + ". " + r.name + "   (geometry " + r.geometry_hash + ")";
    std::ostringstream geo, metrics;
    geo << "n = " << n << ", K = " << r.holes << " ("
        << fmt(100.0 * r.holes / (double(n) * n), "%.1f") << " % open), " << spacing_text(r)
        << "; kernel " << p.kernel << "; " << r.pixels_per_cell << " px per cell, period "
        << px(m, m) << " px";
    metrics << "max sidelobe " << r.max_sidelobe << ", PSR " << ratio(r.peak_to_sidelobe_ratio)
            << ", min|P^| " << ratio(r.min_abs_pattern_spectrum) << ", flatness "
            << ratio(r.spectral_flatness) << ", OTF condition " << ratio(r.otf_condition_number)
            << "; analytic MMSE " << db(r.analytic_mmse_psnr_db) << " dB, analytic Wiener "
            << db(r.analytic_wiener_psnr_db) << " dB (NSR " << fmt(r.analytic_wiener_nsr, "%.3g")
            << ")"
            << (std::isnan(r.analytic_robust_wiener_psnr_db)
                    ? ""
                    : " (robust, under fabrication errors: " +
                          db(r.analytic_robust_wiener_psnr_db) + " dB)")
            << "; mean over scenes: sim Wiener " << db(r.sim_wiener_psnr_db) << " dB / SSIM "
            << ssim_text(r.sim_wiener_ssim) << ", sim TV " << db(r.sim_tv_psnr_db) << " dB / SSIM "
            << ssim_text(r.sim_tv_ssim);
    page.lines = {(r.kind == "input" ? "File: " : "Baseline: ") + r.source, geo.str(),
                  metrics.str()};
    if (r.metrics.spectral_zero->found)
        page.lines.push_back("WARNING: " + r.metrics.spectral_zero->message());

    ReportPanel pattern = panel("Pattern (white = clear)", p.pattern, 0.0, 1.0,
                                px(n, n) + " cells of " + format_length(camera.pinhole_m));
    pattern.colorbar = false;
    page.panels.push_back(pattern);
    page.panels.push_back(
        panel("PSF, one period", p.psf, 0.0, p.psf.maxCoeff(),
              px(m, m) + " px of " + format_length(camera.pixel_pitch_m) + ", sum 1"));
    auto [olo, ohi] = finite_range(p.log_otf);
    constexpr double kOtfFloorDecades = -6.0;  // darker than 1e-6 of DC reads as "zero"
    olo = std::max(olo, kOtfFloorDecades);
    if (!(olo < ohi)) olo = ohi - 1.0;
    ReportPanel otf = panel("log10 |OTF| / |OTF(0)|", p.log_otf, olo, ohi,
                            px(m, m) + " frequencies, zero at centre");
    otf.unit = "";
    page.panels.push_back(otf);
    // Sidelobes only: the grey range spans min..max over d != 0 (the peak K is off scale).
    Plane sidelobes = p.autocorrelation;
    sidelobes(n / 2, n / 2) = r.max_sidelobe;
    const double sl_lo = sidelobes.minCoeff();
    const double sl_hi = std::max(sl_lo + 1.0, static_cast<double>(r.max_sidelobe));
    page.panels.push_back(
        panel("Autocorrelation R(d)", p.autocorrelation, sl_lo, sl_hi,
              "shift 0 at centre; R(0) = " + std::to_string(r.holes) + " off scale"));
    page.panels.push_back(panel("Scene: " + p.scene_name, p.scene, 0.0, 1.0, px(m, m) + " px"));
    const auto [clo, chi] = finite_range(p.capture);
    page.panels.push_back(panel("Capture, " + noise_caption(s.metrics.noise.front().model),
                                p.capture, clo, chi,
                                "mean noise sigma " + fmt(p.capture_sigma, "%.3g")));
    page.panels.push_back(
        panel("Wiener, NSR " + fmt(r.sim_wiener_nsr, "%.3g"), p.wiener, 0.0, 1.0,
              "this capture (grey clipped to 0..1):",
              {"PSNR " + db(p.wiener_psnr_db) + " dB, SSIM " + ssim_text(p.wiener_ssim)}));
    page.panels.push_back(
        panel("TV-L2, lambda " + fmt(r.sim_tv_lambda, "%.3g"), p.tv, 0.0, 1.0,
              "this capture, " + std::to_string(p.tv_iterations) + " iterations:",
              {"PSNR " + db(p.tv_psnr_db) + " dB, SSIM " + ssim_text(p.tv_ssim)}));
    return page;
}

}  // namespace

std::string noise_caption(const NoiseModel& m) {
    if (m.kind == NoiseKind::kPhoton) {
        return "photon model, " + fmt(m.photons_per_pinhole, "%g") + " e per pinhole";
    }
    if (m.kind == NoiseKind::kGaussianSnr) return "SNR " + fmt(m.snr_db, "%g") + " dB";
    return "noiseless";
}

ReportTable compare_table(const std::vector<CompareResult>& results, const std::string& lead) {
    const bool mmse = lead == "analytic_mmse_psnr_db";
    const std::string other = mmse ? "analytic_wiener_psnr_db" : "analytic_mmse_psnr_db";
    const auto short_name = [](const std::string& f) {
        return f == "analytic_mmse_psnr_db" ? std::string("analytic MMSE") : "analytic W";
    };
    ReportTable t;
    t.headers = {
        "mask",  "K",       "n",        "spacing", short_name(lead), "vs 1st",  short_name(other),
        "sim W", "vs 1st",  "W SSIM",   "sim TV",  "vs 1st",         "TV SSIM", "max SL",
        "PSR",   "min|P^|", "flatness", "zero",    "OTF cond"};
    t.units = {"",        "",         "", "ok?",     "PSNR dB",  "dB", "PSNR dB",
               "PSNR dB", "dB +- SE", "", "PSNR dB", "dB +- SE", "",   "",
               "",        "",         "", "freq",    ""};
    const auto diff = [](const CompareRow& r, const std::string& name) -> std::string {
        for (const auto& [n, d] : r.to_first)
            if (n == name) return difference_text(d);
        return "-";
    };
    for (const CompareResult& res : results) {
        const CompareRow& r = res.row;
        t.rows.push_back({r.name, std::to_string(r.holes), std::to_string(r.n),
                          r.spacing_ok ? "yes" : "NO", db(row_figure(r, lead)), diff(r, lead),
                          db(row_figure(r, other)), db(r.sim_wiener_psnr_db),
                          diff(r, "sim_wiener_psnr_db"), ssim_text(r.sim_wiener_ssim),
                          db(r.sim_tv_psnr_db), diff(r, "sim_tv_psnr_db"), ssim_text(r.sim_tv_ssim),
                          std::to_string(r.max_sidelobe), ratio(r.peak_to_sidelobe_ratio),
                          ratio(r.min_abs_pattern_spectrum), ratio(r.spectral_flatness),
                          zero_text(r), ratio(r.otf_condition_number)});
    }
    // With --robust: the robust analytic figure beside the analytic ones.
    const bool robust = std::any_of(results.begin(), results.end(), [](const CompareResult& r) {
        return !std::isnan(r.row.analytic_robust_wiener_psnr_db);
    });
    if (robust) {
        const std::size_t at = 7;  // after the second analytic figure
        t.headers.insert(t.headers.begin() + at, "robust W");
        t.units.insert(t.units.begin() + at, "PSNR dB");
        for (std::size_t i = 0; i < results.size(); ++i)
            t.rows[i].insert(t.rows[i].begin() + at,
                             db(results[i].row.analytic_robust_wiener_psnr_db));
    }
    // With the depth group: the worst Cramer-Rao bound on the distance, first level.
    const auto depth = [](const CompareResult& r) -> const DepthFigures* {
        const auto& levels = r.row.metrics.levels;
        return levels.empty() || !levels.front().depth ? nullptr : &*levels.front().depth;
    };
    if (std::any_of(results.begin(), results.end(), depth)) {
        t.headers.insert(t.headers.end(), {"depth", "axial FWHM"});
        t.units.insert(t.units.end(), {"sigma_u/u", "m"});
        for (std::size_t i = 0; i < results.size(); ++i) {
            const DepthFigures* d = depth(results[i]);
            t.rows[i].push_back(d ? fmt(d->crb_rel, "%.3g") : "-");
            t.rows[i].push_back(d ? fmt(d->axial_fwhm_m, "%.3g") : "-");
        }
    }
    return t;
}

std::string compare_holes_text(const std::vector<CompareResult>& results) {
    std::vector<const CompareRow*> rows;
    for (const CompareResult& r : results) rows.push_back(&r.row);
    std::stable_sort(rows.begin(), rows.end(),
                     [](const CompareRow* a, const CompareRow* b) { return a->holes < b->holes; });
    if (rows.empty() || rows.front()->holes == rows.back()->holes) return "";
    std::ostringstream s;
    s << "PSNR against pinhole count (light gain = K x one pinhole's light):\n";
    for (const CompareRow* r : rows) {
        s << "  K " << r->holes << "  light " << r->holes << "x  analytic MMSE "
          << db(r->analytic_mmse_psnr_db) << " dB  analytic W " << db(r->analytic_wiener_psnr_db)
          << " dB  sim W " << db(r->sim_wiener_psnr_db) << " dB  " << r->name << "\n";
    }
    return s.str();
}

ReportDocument compare_document(const std::vector<CompareResult>& results, const CompareSettings& s,
                                const CompareSummary& summary) {
    const Camera& c = summary.camera;
    ReportDocument d;
    d.title = "pinmask compare: " + std::to_string(results.size()) + " masks";
    std::ostringstream cam;
    cam << "Camera: object distance u = " << format_length(c.object_distance_m)
        << ", lens focal length f' = " << format_length(c.lens_focal_m)
        << ", lens-sensor distance f = " << format_length(c.sensor_distance_m)
        << ", pinhole d = " << format_length(c.pinhole_m)
        << ", pixel pitch w = " << format_length(c.pixel_pitch_m) << ", wavelength "
        << format_length(c.wavelength_m) << ", sensor " << c.sensor_cols << " x " << c.sensor_rows
        << " px; pixels per cell at u, d |1 - f/f' + f/u| / w = "
        << fmt(pixels_per_cell_at(c, c.object_distance_m), "%.2f") << ".";
    d.lines.push_back(cam.str());
    for (const auto& l : summary.settings_lines) d.lines.push_back(l);
    for (const auto& l : summary.baseline_lines) d.lines.push_back(l);
    d.lines.push_back("The table leads with " + summary.lead.name + " (" +
                      figure_words(summary.lead.name) + "): " + summary.lead.reason + ".");
    d.table = compare_table(results, summary.lead.name);
    const MaskMetricsOptions& mo = s.metrics;
    d.notes = {
        "Columns. K: pinholes. n: cells per side of the cyclic pattern. spacing ok?: no two "
        "pinhole centres closer than the mask's minimum spacing on the torus (across tile "
        "seams).",
        "max SL: largest torus autocorrelation sidelobe R(d), d != 0. PSR: R(0) / max SL = K / "
        "max SL. min|P^|: smallest magnitude of the pattern's n x n DFT over k != 0. flatness: "
        "geometric / arithmetic mean of |P^|^2 over k != 0 (1 = flat, 0 = a spectral zero). "
        "zero: the pattern frequency of a spectral zero (|P^| < 1e-3 sqrt(K) where the kernel "
        "passes light), none otherwise.",
        "OTF cond: max / min |A^| of the mask OTF over the kernel passband (|K^| >= 0.1 max |K^|); "
        "inf = an exact zero.",
        "analytic MMSE (analytic_mmse_psnr_db): expected PSNR in closed form over one period "
        "under the prior, decoded by the per-frequency optimal (MMSE) Wiener filter, which no "
        "linear decoder beats: the figure search optimises under Gaussian noise. analytic W "
        "(analytic_wiener_psnr_db): the same, decoded by Wiener of one NSR (" +
            (mo.simulation.wiener_nsr.tuned ? std::string("tuned per mask")
                                            : "NSR " + fmt(mo.simulation.wiener_nsr.value, "%g")) +
            "): the figure search optimises under the photon model. Both " + summary.noise_text +
            " (the first level), prior " + mo.prior.description() +
            "; pinmask score prints them under the same names.",
        "vs 1st: each mask minus the first mask on the figure to its left. Analytic figures are "
        "closed forms, so their differences are exact. Simulated ones are paired over the scenes "
        "(the same scenes and noise draws for every mask): mean difference +- the standard error "
        "of the mean (sd / sqrt(scenes)); n.s. = not significant, under two standard errors.",
        "sim W / sim TV (sim_wiener_psnr_db, sim_tv_psnr_db): one period of each scene through the "
        "PSF (cyclic model) with " +
            summary.noise_text +
            " (the first level), decoded by Wiener and TV-L2; PSNR = 10 log10(1 / MSE) for scenes "
            "in [0, 1], SSIM with an 11 x 11 Gaussian window; means over the scenes (" +
            scene_list(mo) + "). Each mask is simulated on its own period m = n x pixels per cell.",
    };
    const std::string holes = compare_holes_text(results);
    if (!holes.empty()) d.notes.push_back(holes);
    for (std::size_t i = 0; i < results.size(); ++i)
        d.pages.push_back(mask_page(results[i], i, c, s));
    return d;
}

}  // namespace pinmask
