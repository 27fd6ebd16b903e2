#include "cli/outputs/sweep_outputs.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "core/files/atomic_file.hpp"
#include "core/units/number_format.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "report/sweep_plot.hpp"

namespace pinmask::cli {
namespace fs = std::filesystem;

namespace {

double score(const SweepPointResult& r, const char* key) {
    const auto it = r.scores.find(key);
    return it == r.scores.end() ? NAN : it->second;
}

std::string point_name(std::size_t i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "point-%04zu", i);
    return buf;
}

// The light level of a point: photons per pinhole (photon model) or the SNR (Gaussian).
double light_level(const SearchPipelineOptions& o) {
    return o.noise.kind == NoiseKind::kPhoton ? o.noise.photons_per_pinhole : o.noise.snr_db;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

std::string sweep_csv(const io::SweepConfig& sweep, const std::vector<SweepRow>& rows) {
    std::ostringstream s;
    s << "point";
    for (const auto& k : sweep.keys) s << "," << csv_field(k);
    s << ",K,pinhole_m,noise_model,light_level,objective,analytic_mmse_psnr_db,"
         "analytic_wiener_psnr_db,sim_wiener_psnr_db,sim_tv_psnr_db,evaluations,geometry_hash,"
         "mask\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        s << i;
        for (const auto& v : r.point->values) s << "," << csv_field(v.text);
        const Mask m = sweep_best_mask(*r.options, r.result);
        s << "," << r.options->holes << "," << format_cell(r.options->tmpl.camera.pinhole_m, "%.9g")
          << "," << (r.options->noise.kind == NoiseKind::kPhoton ? "photon" : "gaussian") << ","
          << format_cell(light_level(*r.options), "%.9g") << ","
          << format_cell(r.result.objective, "%.9g") << ","
          << format_cell(score(r.result, "analytic_mmse_psnr_db"), "%.9g") << ","
          << format_cell(score(r.result, "analytic_wiener_psnr_db"), "%.9g") << ","
          << format_cell(score(r.result, "sim_wiener_psnr_db"), "%.9g") << ","
          << format_cell(score(r.result, "sim_tv_psnr_db"), "%.9g") << "," << r.result.evaluations
          << "," << geometry_hash(m) << ",points/" << point_name(i) << ".mask.json\n";
    }
    return s.str();
}

struct Axis {
    const char* name;  // file stem
    const char* x_label;
    std::vector<std::string> keys;  // the sweep keys that move this axis
    double (*value)(const SearchPipelineOptions&);
};

const std::vector<Axis>& axes() {
    static const std::vector<Axis> a{
        {"psnr-vs-holes",
         "K (pinholes)",
         {"holes"},
         [](const SearchPipelineOptions& o) { return double(o.holes); }},
        {"psnr-vs-pinhole-size",
         "pinhole size (m)",
         {"optics.pinhole_m"},
         [](const SearchPipelineOptions& o) { return o.tmpl.camera.pinhole_m; }},
        {"psnr-vs-light",
         "light level (photons per pinhole, or SNR dB for Gaussian noise)",
         {"noise.photons_per_pinhole", "noise.snr_db", "noise.model"},
         light_level}};
    return a;
}

// The plot of one axis: a series per combination of the other varied keys' values.
SweepPlot axis_plot(const Axis& axis, const io::SweepConfig& sweep,
                    const std::vector<SweepRow>& rows) {
    SweepPlot plot{"best mask per design point: analytic MMSE PSNR",
                   axis.x_label,
                   "analytic MMSE PSNR (dB)",
                   {}};
    std::map<std::string, std::size_t> series_of;
    for (const SweepRow& r : rows) {
        std::string label;
        for (std::size_t k = 0; k < sweep.keys.size(); ++k) {
            bool on_axis = false;
            for (const auto& a : axis.keys) on_axis = on_axis || a == sweep.keys[k];
            if (on_axis) continue;
            label += (label.empty() ? "" : ", ") + sweep.keys[k] + "=" + r.point->values[k].text;
        }
        auto [it, fresh] = series_of.emplace(label, plot.series.size());
        if (fresh) plot.series.push_back({label, {}});
        plot.series[it->second].points.emplace_back(axis.value(*r.options),
                                                    score(r.result, "analytic_mmse_psnr_db"));
    }
    return plot;
}

}  // namespace

std::vector<fs::path> sweep_table_paths(const fs::path& dir, std::size_t points) {
    std::vector<fs::path> out{dir / "sweep.csv", dir / "sweep.md", dir / "sweep.config.json"};
    for (std::size_t i = 0; i < points; ++i) {
        out.push_back(dir / "points" / (point_name(i) + ".mask.json"));
        out.push_back(dir / "points" / (point_name(i) + ".search.config.json"));
    }
    return out;
}

std::string sweep_markdown(const io::SweepConfig& sweep, const std::vector<SweepRow>& rows) {
    std::ostringstream s;
    s << "| point |";
    for (const auto& k : sweep.keys) s << " " << k << " |";
    s << " objective | analytic MMSE PSNR (dB) | analytic Wiener PSNR (dB; filter tuned or "
         "fixed) | simulated Wiener PSNR (dB) | simulated TV PSNR (dB) | evaluations | geometry "
         "hash |\n|---:|";
    for (std::size_t k = 0; k < sweep.keys.size(); ++k) s << "---|";
    s << "---:|---:|---:|---:|---:|---:|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const SweepRow& r = rows[i];
        s << "| " << i << " |";
        for (const auto& v : r.point->values) s << " " << v.text << " |";
        s << " " << format_cell(r.result.objective, "%.4f") << " | "
          << format_cell(score(r.result, "analytic_mmse_psnr_db")) << " | "
          << format_cell(score(r.result, "analytic_wiener_psnr_db")) << " | "
          << format_cell(score(r.result, "sim_wiener_psnr_db")) << " | "
          << format_cell(score(r.result, "sim_tv_psnr_db")) << " | " << r.result.evaluations
          << " | " << geometry_hash(sweep_best_mask(*r.options, r.result)) << " |\n";
    }
    return s.str();
}

std::vector<fs::path> write_sweep_outputs(const fs::path& dir, const io::SweepConfig& sweep,
                                          const std::vector<SweepRow>& rows) {
    fs::create_directories(dir / "points");
    StagedFiles files;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Mask mask = sweep_best_mask(*rows[i].options, rows[i].result);
        const fs::path stem = dir / "points" / point_name(i);
        files.stage(fs::path(stem.string() + ".mask.json"),
                    [&](const fs::path& tmp) { io::write_mask_file(tmp, mask); });
        files.stage_bytes(fs::path(stem.string() + ".search.config.json"),
                          io::json_strict::pretty(rows[i].config) + "\n");
    }
    files.stage_bytes(dir / "sweep.csv", sweep_csv(sweep, rows));
    files.stage_bytes(dir / "sweep.md", "# Sweep\n\n" + sweep_markdown(sweep, rows));
    files.stage_bytes(dir / "sweep.config.json", sweep.text + "\n");
    std::vector<fs::path> plots;
    for (const Axis& axis : axes()) {
        std::set<double> xs;
        for (const SweepRow& r : rows) xs.insert(axis.value(*r.options));
        if (xs.size() < 2) continue;  // this axis does not vary
        const SweepPlot plot = axis_plot(axis, sweep, rows);
        const fs::path svg = dir / (std::string(axis.name) + ".svg");
        const fs::path png = dir / (std::string(axis.name) + ".png");
        files.stage(svg, [&](const fs::path& tmp) { write_sweep_plot_svg(tmp, plot); });
        files.stage(png, [&](const fs::path& tmp) { write_sweep_plot_png(tmp, plot); });
        plots.push_back(svg);
        plots.push_back(png);
    }
    files.commit();
    return plots;
}

}  // namespace pinmask::cli
