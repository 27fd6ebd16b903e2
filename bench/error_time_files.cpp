#include "bench/error_time_files.hpp"

#include "bench/error_time_plot.hpp"
#include "bench/error_time_report.hpp"
#include "core/files/atomic_file.hpp"

namespace pinmask {

namespace fs = std::filesystem;

ErrorTimeFiles write_error_time_files(const fs::path& out_dir, const ErrorTimeResult& r,
                                      const std::string& config_text) {
    fs::create_directories(out_dir);
    StagedFiles files;
    files.stage_bytes(out_dir / "error_time.csv", error_time_csv(r.records));
    files.stage_bytes(out_dir / "error_time_points.csv", error_time_points_csv(r.points));
    files.stage_bytes(out_dir / "error_time.md", r.markdown);
    ErrorTimeFiles out;
    for (const ErrorTimeNamedPlot& p : r.plots) {
        files.stage(out_dir / (p.stem + ".svg"),
                    [&](const fs::path& tmp) { write_error_time_svg(tmp, p.plot); });
        files.stage(out_dir / (p.stem + ".png"),
                    [&](const fs::path& tmp) { write_error_time_png(tmp, p.plot); });
        out.plots.push_back((out_dir / (p.stem + ".svg")).string());
        out.plots.push_back((out_dir / (p.stem + ".png")).string());
    }
    files.stage_bytes(out_dir / "error_time.config.json", config_text);
    files.commit();
    out.count = files.final_paths().size();
    return out;
}

}  // namespace pinmask
