#include "decode/calibrate/report.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/errors/error.hpp"
#include "core/image/cairo_handles.hpp"
#include "core/version.hpp"

namespace pinmask::calibrate {

namespace {

constexpr double kPageW = 595.0, kPageH = 842.0, kMargin = 40.0;  // A4, points
constexpr char kPinnedDate[] = "2000-01-01T00:00:00Z";
constexpr int kRowsPerTablePage = 48;

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, a, b, c);
    return buf;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size = 9) {
    cairo_set_font_size(cr, size);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s.c_str());
}

// Draws `p` mapped linearly from [lo, hi] to black..white into the box (x, y, w, h), keeping the
// aspect ratio; returns the scale (points per pixel).
double draw_plane(cairo_t* cr, const Plane& p, double lo, double hi, double x, double y, double w,
                  double h) {
    const int rows = static_cast<int>(p.rows()), cols = static_cast<int>(p.cols());
    cairo::SurfacePtr img(cairo_image_surface_create(CAIRO_FORMAT_RGB24, cols, rows));
    cairo_surface_flush(img.get());
    unsigned char* data = cairo_image_surface_get_data(img.get());
    const int stride = cairo_image_surface_get_stride(img.get());
    const double span = hi > lo ? hi - lo : 1.0;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double v = std::clamp((p(r, c) - lo) / span, 0.0, 1.0);
            const auto g = static_cast<std::uint32_t>(std::lround(255 * v));
            reinterpret_cast<std::uint32_t*>(data + r * stride)[c] = (g << 16) | (g << 8) | g;
        }
    cairo_surface_mark_dirty(img.get());
    const double scale = std::min(w / cols, h / rows);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, img.get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    return scale;
}

double percentile(const Plane& p, double q) {
    std::vector<double> v(p.data(), p.data() + p.size());
    const auto k = static_cast<std::size_t>(q * (v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

}  // namespace

std::string calibration_report_pdf(const Plane& capture, const CalibrationSummary& s,
                                   const std::string& title) {
    std::string out;
    {
        cairo::SurfacePtr surface(
            cairo_pdf_surface_create_for_stream(append, &out, kPageW, kPageH));
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, title.c_str());
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR,
                                       "pinmask " PINMASK_VERSION);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, kPinnedDate);
        cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_MOD_DATE, kPinnedDate);
        cairo::ContextPtr ctx(cairo_create(surface.get()));
        cairo_t* cr = ctx.get();
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        const double box = kPageW - 2 * kMargin;

        // Page 1: overlay.
        cairo_set_source_rgb(cr, 0, 0, 0);
        text(cr, kMargin, kMargin, title + ": predicted and measured spots", 12);
        const double lo = percentile(capture, 0.01), hi = percentile(capture, 0.999);
        const double top = kMargin + 15;
        const double sc = draw_plane(cr, capture, lo, hi, kMargin, top, box, box);
        const double rad = 0.5 * s.pitch_x_px * sc;
        for (const auto& p : s.fit.pinholes) {
            if (!p.in_frame) continue;
            if (p.missing)
                cairo_set_source_rgb(cr, 0.9, 0.1, 0.1);
            else
                cairo_set_source_rgb(cr, 0.1, 0.8, 0.1);
            cairo_set_line_width(cr, 0.8);
            cairo_new_sub_path(cr);
            cairo_arc(cr, kMargin + (p.x + 0.5) * sc, top + (p.y + 0.5) * sc, rad, 0, 2 * M_PI);
            cairo_stroke(cr);
        }
        auto cross = [&](double x, double y) {
            const double px = kMargin + (x + 0.5) * sc, py = top + (y + 0.5) * sc, a = 2.5;
            cairo_move_to(cr, px - a, py);
            cairo_line_to(cr, px + a, py);
            cairo_move_to(cr, px, py - a);
            cairo_line_to(cr, px, py + a);
            cairo_stroke(cr);
        };
        cairo_set_source_rgb(cr, 0.2, 0.4, 1.0);
        for (const auto& e : s.extra_spots) cross(e[0], e[1]);
        cairo_set_source_rgb(cr, 0, 0, 0);
        double y = top + capture.rows() * sc + 20;
        const auto& f = s.fit;
        const double pd = s.design_pitch_px;
        const std::vector<std::string> lines = {
            "fit of the forward model to the whole capture; +- are standard errors (Fisher "
            "information x chi2/dof)",
            "rotation is counter-clockwise on screen with rows running down "
            "(scipy.ndimage.rotate's sense)",
            "quantity                 measured            +- sigma      design",
            fmt("rotation (deg)           %-18.5f  %-12.5f  %.1f", s.rotation_deg,
                s.rotation_sigma_deg, 0.0),
            fmt("pitch x (px)             %-18.5f  %-12.5f  %.4f", s.pitch_x_px, s.pitch_x_sigma_px,
                pd),
            fmt("pitch y (px)             %-18.5f  %-12.5f  %.4f", s.pitch_y_px, s.pitch_y_sigma_px,
                pd),
            fmt("pinhole side (x design)  %-18.5f  %-12.5f  %.1f", f.side_scale, f.side_scale_sigma,
                1.0),
            fmt("cell (0, 0) x, y (px)    %-9.3f %-8.3f  %-12.4f", s.position_x_px, s.position_y_px,
                s.position_sigma_px),
            fmt("leak (counts/px)         %-18.5g  %-12.4g", s.background, s.background_sigma),
            std::string(s.optical_density_is_bound ? "optical density > " : "optical density ") +
                fmt("%.3f", s.optical_density) +
                (s.optical_density_is_bound ? "" : fmt(" +- %.3f", s.optical_density_sigma)) +
                fmt(", dark level %.4g, noise var = %.4g m + %.4g", s.dark_level, f.noise_alpha,
                    f.noise_beta),
            fmt("pinholes fitted %.0f, missing %.0f, extra spots %.0f", f.pinholes.size(),
                s.missing.size(), s.extra_spots.size()) +
                fmt(", chi2/dof %.3f, unexplained %.4f", f.chi2_reduced, f.unexplained),
            fmt("missing: gain + %.2f sigma < median gain / 2 (false alarm %.0e per pinhole)",
                f.missing_z, 0.5 * std::erfc(f.missing_z / std::sqrt(2.0))),
            "coverage: the 95 % intervals of rotation and pitch are tested to cover the truth in "
            ">= 90 of 100 seeded trials (tests/calibrate)",
            "circles: fitted sites (green found, red missing); crosses: extra light (blue)"};
        for (const auto& l : lines) {
            text(cr, kMargin, y, l);
            y += 13;
        }
        cairo_show_page(cr);

        // Page 2: residual map and kernel comparison.
        text(cr, kMargin, kMargin, title + ": residual map and kernel models", 12);
        const double m = std::max(std::abs(percentile(s.residual_map, 0.001)),
                                  std::abs(percentile(s.residual_map, 0.999)));
        const double sc2 =
            draw_plane(cr, s.residual_map, -m, m, kMargin, kMargin + 15, box, 0.5 * kPageH);
        y = kMargin + 15 + s.residual_map.rows() * sc2 + 16;
        text(cr, kMargin, y,
             fmt("residual: capture - fitted model, grey = 0, "
                 "range +- %.4g counts",
                 m));
        y += 14;
        const double tile = 90;
        const double kmax = s.kernel.values.maxCoeff();
        double x = kMargin;
        draw_plane(cr, s.kernel.values, 0, kmax, x, y, tile, tile);
        text(cr, x, y + tile + 12, "measured");
        for (const auto& f : s.kernel_fit) {
            x += tile + 10;
            if (f.available) {
                draw_plane(cr, f.values, 0, kmax, x, y, tile, tile);
                text(cr, x, y + tile + 12, f.model + fmt(": %.4f", f.residual));
            } else {
                text(cr, x, y + 0.5 * tile, f.model + ": not available");
            }
        }
        text(cr, kMargin, y + tile + 28,
             "residual = ||measured - model||2 / ||measured||2; best: " + s.best_model);
        cairo_show_page(cr);

        // Pages 3+: per-pinhole table.
        cairo_select_font_face(cr, "monospace", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        const int n = static_cast<int>(f.pinholes.size());
        for (int start = 0; start < n; start += kRowsPerTablePage) {
            text(cr, kMargin, kMargin, title + ": pinholes (mask cell row, col over the tiles)",
                 12);
            y = kMargin + 20;
            text(cr, kMargin, y,
                 "row  col  state     fitted x, y          gain          +- sigma    gain/median");
            for (int i = start; i < std::min(n, start + kRowsPerTablePage); ++i) {
                const auto& r = f.pinholes[i];
                y += 14;
                char buf[200];
                std::snprintf(buf, sizeof buf,
                              "%3d  %3d  %-8s  %8.2f %8.2f    %-12.5g  %-10.3g  %.3f",
                              r.mask_cell.row, r.mask_cell.col,
                              !r.in_frame ? "edge"
                              : r.missing ? "missing"
                                          : "found",
                              r.x, r.y, r.gain, r.gain_sigma,
                              f.median_gain > 0 ? r.gain / f.median_gain : 0.0);
                text(cr, kMargin, y, buf, 8);
            }
            cairo_show_page(cr);
        }
        if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
            throw RuntimeFailure(std::string("calibration report: ") +
                                 cairo_status_to_string(cairo_status(cr)));
        ctx.reset();
        cairo_surface_finish(surface.get());
    }
    return out;
}

}  // namespace pinmask::calibrate
