#include "io/depth_json.hpp"

#include "core/files/atomic_file.hpp"
#include "io/json_strict.hpp"
#include "report/depth_plot.hpp"

namespace pinmask::io {

namespace fs = std::filesystem;
using json_strict::finite_or_null;

nlohmann::ordered_json depth_json(const std::vector<DepthRecord>& records) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const DepthRecord& r : records) {
        j.push_back({{"object_distance_m", finite_or_null(r.object_distance_m)},
                     {"pixels_per_cell", r.pixels_per_cell},
                     {"period_px", r.period_px},
                     {"lsi_mismatch_px", r.lsi_mismatch_px},
                     {"wiener_psnr_loss_db", finite_or_null(r.wiener_psnr_loss_db)},
                     {"tv_psnr_loss_db", finite_or_null(r.tv_psnr_loss_db)},
                     {"wiener_nsr", r.wiener_nsr}});
    }
    return j;
}

std::vector<fs::path> write_depth_files(const fs::path& dir,
                                        const std::vector<DepthRecord>& records, double design_u_m,
                                        const std::string& title, nlohmann::ordered_json config) {
    fs::create_directories(dir);
    StagedFiles files;
    files.stage(dir / "depth.svg",
                [&](const fs::path& tmp) { write_depth_svg(tmp, records, design_u_m, title); });
    files.stage(dir / "depth.png",
                [&](const fs::path& tmp) { write_depth_png(tmp, records, design_u_m, title); });
    config["records"] = depth_json(records);
    files.stage_bytes(dir / "depth.json", config.dump(2) + "\n");
    files.commit();
    return files.final_paths();
}

}  // namespace pinmask::io
