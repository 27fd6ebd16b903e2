#include "bench/error_time_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pinmask {
namespace {

std::string g6(double v) {
    if (std::isnan(v)) return "nan";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string fixed(double v, int digits) {
    if (std::isnan(v)) return "n/a";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// Seconds with 2 significant digits in plain notation (0.0041, 0.27, 3.1).
std::string seconds_text(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2g", s);
    return buf;
}

}  // namespace

std::string error_time_csv(const std::vector<ErrorTimeRecord>& records) {
    std::ostringstream s;
    s << "snr_db,scene,decoder,parameter,value,iterations,iterations_run,converged,seconds,"
         "wall_seconds,timing_runs,psnr_db,ssim\n";
    for (const auto& r : records) {
        s << g6(r.snr_db) << ',' << r.scene << ',' << r.decoder << ',' << r.parameter << ','
          << g6(r.value) << ',' << r.iterations << ',' << r.iterations_run << ','
          << (r.converged ? 1 : 0) << ',' << g6(r.seconds) << ',' << g6(r.wall_seconds) << ','
          << r.timing_runs << ',' << g6(r.psnr_db) << ',' << g6(r.ssim) << '\n';
    }
    return s.str();
}

std::string error_time_points_csv(const std::vector<ErrorTimePoint>& points) {
    std::ostringstream s;
    s << "snr_db,decoder,parameter,value,iterations,seconds,wall_seconds,psnr_db,ssim,scenes\n";
    for (const auto& p : points) {
        s << g6(p.snr_db) << ',' << p.decoder << ',' << p.parameter << ',' << g6(p.value) << ','
          << p.iterations << ',' << g6(p.seconds) << ',' << g6(p.wall_seconds) << ','
          << g6(p.psnr_db) << ',' << g6(p.ssim) << ',' << p.scenes << '\n';
    }
    return s.str();
}

std::string error_time_markdown(const std::vector<DecoderSummary>& summary) {
    std::vector<double> snrs;
    for (const auto& d : summary) {
        if (std::find(snrs.begin(), snrs.end(), d.best.snr_db) == snrs.end())
            snrs.push_back(d.best.snr_db);
    }
    auto iterations = [](const ErrorTimePoint& p) {
        return p.iterations > 0 ? std::to_string(p.iterations) : std::string("closed form");
    };
    std::ostringstream s;
    for (double snr : snrs) {
        if (snrs.size() > 1) s << "### SNR " << g6(snr) << " dB\n\n";
        s << "| decoder | setting | iterations | time (s) | PSNR (dB) | SSIM | within "
          << g6(kNearBestDb) << " dB of best |\n"
          << "|---|---|---:|---:|---:|---:|---|\n";
        for (const auto& d : summary) {
            const ErrorTimePoint& p = d.best;
            if (p.snr_db != snr) continue;
            const std::string setting = p.parameter.empty() ? "-" : p.parameter + " " + g6(p.value);
            const std::string near = p.iterations == 0
                                         ? "-"
                                         : iterations(d.near_best) + " iterations, " +
                                               seconds_text(d.near_best.seconds) + " s";
            s << "| " << p.decoder << " | " << setting << " | " << iterations(p) << " | "
              << seconds_text(p.seconds) << " | " << fixed(p.psnr_db, 2) << " | "
              << fixed(p.ssim, 3) << " | " << near << " |\n";
        }
        s << "\n";
    }
    s << "Time: CPU seconds of one decode on one thread (median of repeats for fast points). "
         "PSNR and SSIM: mean over scenes. Paper's reference timings (its own machine and "
         "code): Wiener "
      << g6(kPaperWienerSeconds) << " s, TVQC " << g6(kPaperTvqcSeconds) << " s.\n";
    return s.str();
}

}  // namespace pinmask
