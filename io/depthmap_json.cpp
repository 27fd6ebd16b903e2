#include "io/depthmap_json.hpp"

#include <sstream>

#include "core/files/atomic_file.hpp"
#include "core/image/image_io.hpp"
#include "core/units/number_format.hpp"
#include "core/units/units.hpp"
#include "decode/depthmap/depthmap_picture.hpp"
#include "decode/solvers/decode_modes.hpp"
#include "io/json_strict.hpp"

namespace pinmask::io {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using json_strict::finite_or_null;

constexpr const char* kFiles[] = {"depth.tif",        "confidence.tif", "cost_margin.tif",
                                  "all_in_focus.tif", "depthmap.png",   "depthmap.json"};

json name_or_null(const std::string& name) { return name.empty() ? json(nullptr) : json(name); }

// The sweep's range and count (given or chosen: decode/depthmap/depthmap_planes) and the depth
// resolution over it; null for a PSF stack.
json sweep_json(const std::optional<DepthmapPlaneChoice>& p) {
    if (!p) return nullptr;
    return json{{"from_m", p->from_m},
                {"from", p->from_given ? "given" : "design usable range"},
                {"to_m", finite_or_null(p->to_m)},
                {"to", p->to_given ? "given" : "design usable range"},
                {"steps", p->steps},
                {"steps_from", p->steps_given ? "given" : "resolvable step"},
                {"steps_capped", p->capped},
                {"plane_spacing_inverse_per_m", p->spacing_inverse_per_m},
                {"one_pixel_inverse_per_m", p->one_pixel_inverse_per_m},
                {"crb_fwhm_inverse_per_m", p->crb_fwhm_inverse_per_m},
                {"crb_distance_m", p->crb_distance_m},
                {"crb_photons", kDepthmapResolutionPhotons},
                {"resolvable_inverse_per_m", p->resolvable_inverse_per_m},
                {"finer_than_resolvable", p->finer_than_resolvable},
                {"depth_resolution_near_m", p->resolution_near_m},
                {"depth_resolution_far_m", finite_or_null(p->resolution_far_m)}};
}

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
                {"background", background_mode_name(report.capture_options.background.mode)},
                {"background_counts", report.background},
                {"downsample", report.capture_options.downsample},
                {"sweep", sweep_json(report.planes)},
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

std::string depthmap_text(const DepthmapReport& report) {
    const DepthmapResult& r = report.result;
    std::ostringstream out;
    out << "depth " << format_length(r.depth_min_m) << " .. " << format_length(r.depth_max_m)
        << " (median " << format_length(r.depth_median_m) << "), median confidence "
        << r.confidence_median << "; whole capture " << format_length(r.capture_depth_m)
        << " (confidence " << r.capture_confidence << "); " << r.distances_m.size() << " planes\n";
    if (report.planes) {
        const DepthmapPlaneChoice& c = *report.planes;
        out << "planes " << format_length(c.from_m) << " .. " << format_length(c.to_m)
            << (c.from_given && c.to_given ? "" : " (the design's usable range where not given)")
            << ", " << c.steps << (c.steps_given ? "" : " (one resolvable step apart)")
            << "; depth resolution " << format_length(c.resolution_near_m) << " at "
            << format_length(c.from_m) << ", " << format_length(c.resolution_far_m) << " at "
            << format_length(c.to_m)
            << (c.capped ? " (planes capped at " + std::to_string(kDepthmapMaxDefaultPlanes) + ")"
                         : "")
            << (c.finer_than_resolvable
                    ? "; the planes are closer than the camera resolves (" +
                          format_number(c.resolvable_inverse_per_m / c.spacing_inverse_per_m, 3) +
                          " planes per resolvable step)"
                    : "")
            << "\n";
    }
    return out.str();
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
    files.stage(dir / "cost_margin.tif", [&](const fs::path& tmp) {
        write_tiff(tmp, Image(r.cost_margin), SampleFormat::kFloat32);
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
