#include "io/depthmap_json.hpp"

#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "decode/depthmap/depthmap_picture.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using json_strict::finite_or_null;

constexpr const char* kFiles[] = {"depth.tif", "confidence.tif", "all_in_focus.tif", "depthmap.png",
                                  "depthmap.json"};

json name_or_null(const std::string& name) { return name.empty() ? json(nullptr) : json(name); }

}  // namespace

json depthmap_json(const DepthmapReport& report) {
    const DepthmapResult& r = report.result;
    json planes = json::array();
    for (std::size_t k = 0; k < r.distances_m.size(); ++k) {
        planes.push_back({{"object_distance_m", finite_or_null(r.distances_m[k])},
                          {"pixel_fraction", r.plane_fraction[k]},
                          {"mean_cost", r.plane_cost[k]},
                          {"evidence", r.plane_evidence[k]}});
    }
    return json{{"capture", name_or_null(report.capture_name)},
                {"mask", name_or_null(report.mask_name)},
                {"psf_stack", name_or_null(report.psf_stack_name)},
                {"rows", r.depth_m.rows()},
                {"cols", r.depth_m.cols()},
                {"planes_planned", report.planes_planned},
                {"planes_done", r.distances_m.size()},
                {"interrupted", r.interrupted},
                {"wiener_nsr", report.wiener_nsr},
                {"window_px", report.window},
                {"smooth", report.smooth},
                {"capture_depth_m", finite_or_null(r.capture_depth_m)},
                {"capture_confidence", r.capture_confidence},
                {"capture_evidence_depth_m", finite_or_null(r.capture_evidence_depth_m)},
                {"depth_min_m", finite_or_null(r.depth_min_m)},
                {"depth_median_m", finite_or_null(r.depth_median_m)},
                {"depth_max_m", finite_or_null(r.depth_max_m)},
                {"confidence_median", r.confidence_median},
                {"planes", planes},
                {"files", report.files}};
}

std::vector<fs::path> depthmap_file_paths(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const char* name : kFiles) out.push_back(dir / name);
    return out;
}

void write_depthmap_files(DepthmapReport& report, const fs::path& dir) {
    const DepthmapResult& r = report.result;
    report.files.assign(std::begin(kFiles), std::end(kFiles));
    fs::create_directories(dir);
    StagedFiles files;
    files.stage(dir / "depth.tif", [&](const fs::path& tmp) {
        write_tiff(tmp, Image(r.depth_m), SampleFormat::kFloat32);
    });
    files.stage(dir / "confidence.tif", [&](const fs::path& tmp) {
        write_tiff(tmp, Image(r.confidence), SampleFormat::kFloat32);
    });
    files.stage(dir / "all_in_focus.tif", [&](const fs::path& tmp) {
        write_tiff(tmp, Image(r.all_in_focus), SampleFormat::kFloat32);
    });
    files.stage(dir / "depthmap.png",
                [&](const fs::path& tmp) { write_png(tmp, depthmap_picture(r), 8); });
    files.stage_bytes(dir / "depthmap.json", depthmap_json(report).dump(2) + "\n");
    files.commit();
}

}  // namespace pinmask::io
