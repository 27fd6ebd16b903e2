// `pinmask depthmap CAPTURE --mask M --from U1 --to U2 [--steps N] [--smooth L]` (or
// `--psf-stack STACK` instead of --mask/--from/--to/--steps): a depth map, its confidence and an
// all-in-focus image from one capture, by a plane sweep over object distance
// (decode/depthmap/depthmap.hpp; the stack's format: io/psf_stack.hpp). Writes into -o DIR,
// together: depth.tif (float32, metres), confidence.tif (float32, [0, 1]), all_in_focus.tif
// (float32), depthmap.png (depth in colour and confidence in grey scaled to its maximum, side by
// side, a colour bar from near (dark) to far (bright) at the right), depthmap.json (the summary,
// also on stdout with --json). Ctrl-C stops after the current plane and writes the sweep over the
// planes finished.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/outputs/interrupt.hpp"
#include "cli/outputs/progress.hpp"
#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io.hpp"
#include "core/units/units.hpp"
#include "decode/depthmap/depthmap.hpp"
#include "io/mask_json.hpp"
#include "io/psf_stack.hpp"
#include "optimize/metrics/depth_loss.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

constexpr const char* kOutputFiles[] = {"depth.tif", "confidence.tif", "all_in_focus.tif",
                                        "depthmap.png", "depthmap.json"};

struct DepthmapCommandOptions {
    std::string capture;
    std::string mask;
    std::string psf_stack;
    std::string from, to;
    int steps = 16;
    bool steps_given = false;
    double smooth = kDepthmapDefaultSmooth;
    double nsr = 0.01;
    int window = 121;
    std::string output_dir = "depthmap_out";
    bool json = false;
};

// A blue-to-yellow ramp (dark near, bright far) for t in [0, 1].
void ramp(double t, double& r, double& g, double& b) {
    t = std::clamp(t, 0.0, 1.0);
    r = std::clamp(1.5 * t - 0.25, 0.0, 1.0);
    g = std::clamp(0.15 + 0.8 * t, 0.0, 1.0);
    b = std::clamp(0.55 + 0.5 * t - 1.0 * t * t, 0.0, 1.0);
}

// Depth (colour, by 1/u between the first and last plane) | confidence (grey, scaled to its
// maximum) | colour bar.
Image picture(const DepthmapResult& r) {
    const int rows = static_cast<int>(r.depth_m.rows()), cols = static_cast<int>(r.depth_m.cols());
    const int gap = 8, bar = std::max(8, cols / 16);
    Image out(rows, 2 * cols + 2 * gap + bar, 3);
    for (auto& c : out.channels) c.setOnes();
    auto inv = [](double u) { return std::isinf(u) ? 0.0 : 1.0 / u; };
    const double near = inv(r.distances_m.front()), far = inv(r.distances_m.back());
    // Confidence in grey from 0 (black) to its largest value (white): its values are small when
    // the cost curves are shallow, and the picture shows where it is high.
    const double cmax = r.confidence.maxCoeff() > 0.0 ? r.confidence.maxCoeff() : 1.0;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const double t = near == far ? 0.0 : (inv(r.depth_m(i, j)) - near) / (far - near);
            double cr, cg, cb;
            ramp(t, cr, cg, cb);
            out.channels[0](i, j) = cr;
            out.channels[1](i, j) = cg;
            out.channels[2](i, j) = cb;
            for (int k = 0; k < 3; ++k)
                out.channels[k](i, cols + gap + j) = r.confidence(i, j) / cmax;
        }
        // The bar: near at the top, far at the bottom.
        double cr, cg, cb;
        ramp(rows > 1 ? double(i) / (rows - 1) : 0.0, cr, cg, cb);
        for (int j = 2 * cols + 2 * gap; j < 2 * cols + 2 * gap + bar; ++j) {
            out.channels[0](i, j) = cr;
            out.channels[1](i, j) = cg;
            out.channels[2](i, j) = cb;
        }
    }
    return out;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json summary(const DepthmapResult& r, const DepthmapCommandOptions& o, std::size_t planned) {
    json planes = json::array();
    for (std::size_t k = 0; k < r.distances_m.size(); ++k) {
        planes.push_back({{"object_distance_m", finite_or_null(r.distances_m[k])},
                          {"pixel_fraction", r.plane_fraction[k]},
                          {"mean_cost", r.plane_cost[k]},
                          {"evidence", r.plane_evidence[k]}});
    }
    return json{
        {"capture", o.capture},
        {"mask", o.mask.empty() ? json(nullptr) : json(o.mask)},
        {"psf_stack", o.psf_stack.empty() ? json(nullptr) : json(o.psf_stack)},
        {"rows", r.depth_m.rows()},
        {"cols", r.depth_m.cols()},
        {"planes_planned", planned},
        {"planes_done", r.distances_m.size()},
        {"interrupted", r.interrupted},
        {"wiener_nsr", o.nsr},
        {"window_px", o.window},
        {"smooth", o.smooth},
        {"capture_depth_m", finite_or_null(r.capture_depth_m)},
        {"capture_confidence", r.capture_confidence},
        {"capture_evidence_depth_m", finite_or_null(r.capture_evidence_depth_m)},
        {"depth_min_m", finite_or_null(r.depth_min_m)},
        {"depth_median_m", finite_or_null(r.depth_median_m)},
        {"depth_max_m", finite_or_null(r.depth_max_m)},
        {"confidence_median", r.confidence_median},
        {"planes", planes},
        {"files", std::vector<std::string>(std::begin(kOutputFiles), std::end(kOutputFiles))}};
}

void run(const DepthmapCommandOptions& o) {
    const fs::path dir(o.output_dir);
    check_output_folder(dir, "-o");
    check_plane_source(!o.mask.empty(), !o.psf_stack.empty(), !o.from.empty(), !o.to.empty(),
                       o.steps_given);
    // The stack's files are read first so that the outputs can be checked against them too.
    io::PsfStack stack;
    if (!o.psf_stack.empty()) stack = io::read_psf_stack(o.psf_stack);
    // Before any work: no output may replace an input or another output (core/files/output_set).
    std::vector<NamedPath> outputs;
    for (const char* name : kOutputFiles) outputs.push_back({"-o", dir / name, true});
    std::vector<NamedPath> inputs{{"CAPTURE", o.capture}, {"--mask", o.mask}};
    for (const fs::path& p : stack.files) inputs.push_back({"--psf-stack", p});
    plan_outputs(inputs, outputs);
    Mask mask;
    if (!o.mask.empty()) mask = io::read_mask_file(o.mask);
    LoadedImage loaded = read_image(o.capture);
    Plane grey = Plane::Zero(loaded.image.rows(), loaded.image.cols());
    for (const Plane& ch : loaded.image.channels) grey += ch;
    grey /= static_cast<double>(loaded.image.n_channels());
    if (!is_all_finite(grey)) throw invalid_field("CAPTURE", o.capture, "holds NaN or Inf");
    if (o.window < 3 || o.window % 2 == 0 || o.window > std::min(grey.rows(), grey.cols())) {
        throw invalid_field("--window", std::to_string(o.window),
                            "must be odd, >= 3 and at most the capture's smaller side");
    }
    DepthmapOptions d;
    std::vector<PsfStackPlane> planes;
    if (o.psf_stack.empty()) {
        d.distances_m = depth_range(parse_length_m(o.from, "--from"),
                                    parse_length_m(o.to, "--to", AllowInfinity::kYes), o.steps);
    } else {
        for (std::size_t k = 0; k < stack.psfs.size(); ++k) {
            planes.push_back({stack.distances_m[k], std::move(stack.psfs[k])});
            d.distances_m.push_back(stack.distances_m[k]);
        }
    }
    d.smooth = o.smooth;
    d.wiener_nsr = o.nsr;
    d.window = o.window;
    d.stop = &install_interrupt_flag();
    ProgressLine bar("pinmask depthmap");
    bar.phase("plane sweep over " + std::to_string(d.distances_m.size()) + " distances");
    d.progress = [&](std::size_t done, std::size_t total) {
        bar.update(double(done) / double(total),
                   std::to_string(done) + "/" + std::to_string(total) + " planes");
    };
    const DepthmapResult r =
        o.psf_stack.empty() ? depthmap(grey, mask, d) : depthmap(grey, planes, d);
    bar.finish();
    const json j = summary(r, o, d.distances_m.size());
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
    files.stage(dir / "depthmap.png", [&](const fs::path& tmp) { write_png(tmp, picture(r), 8); });
    files.stage_bytes(dir / "depthmap.json", j.dump(2) + "\n");
    files.commit();
    if (r.interrupted) {
        std::cerr << "depthmap: interrupted after " << r.distances_m.size() << " of "
                  << d.distances_m.size() << " planes: wrote the sweep over those\n";
    }
    if (o.json) {
        std::cout << j.dump(2) << "\n";
        return;
    }
    for (const auto& p : files.final_paths()) std::cerr << "wrote " << p.string() << "\n";
    std::cout << "depth " << format_length(r.depth_min_m) << " .. " << format_length(r.depth_max_m)
              << " (median " << format_length(r.depth_median_m) << "), median confidence "
              << r.confidence_median << "; whole capture " << format_length(r.capture_depth_m)
              << " (confidence " << r.capture_confidence << "); " << r.distances_m.size()
              << " planes\n";
}

constexpr const char* kFooter =
    "Plane sweep: for each of --steps distances from --from to --to (equally spaced in 1/u, the "
    "axis the pattern's scale follows), the capture is decoded (Wiener, scalar --nsr, the "
    "exact-geometry PSF at u over the whole frame, cyclic). Cost: the local energy (box of "
    "--window px) of the residual capture - PSF (*) estimate, which light from another distance "
    "raises. Labels: the plane per pixel that minimises the cost plus --smooth times a penalty "
    "on neighbouring pixels' planes (a one-plane step costs the weight times the mean depth of the "
    "pixels' cost wells, a larger jump twice that; semi-global dynamic programming along 8 "
    "paths; 0: the lowest-cost plane per pixel), refined by a parabola in 1/u; confidence "
    "(median cost - chosen cost) / median cost in [0, 1]; the all-in-focus image takes each "
    "pixel from the decode at its plane. capture_depth_m: the lowest frame-mean cost (the whole "
    "capture as one plane); capture_evidence_depth_m: the lowest evidence (the capture's "
    "marginal likelihood under a 1/f^2 scene prior and white noise). Light from one point spreads "
    "over the whole PSF, so the map resolves "
    "depth only on regions about the PSF's size: measured accuracy in docs/depth.md.\n"
    "--psf-stack STACK replaces --mask/--from/--to/--steps with measured or computed PSFs: a JSON "
    "file (or a folder holding psf_stack.json) {\"format\": \"pinmask-psf-stack\", "
    "\"version\": 1, \"planes\": [{\"object_distance_m\": 0.5, \"psf\": \"psf_0.5m.tif\"}, "
    "...]}: 2-1000 planes at distinct distances > 0 (metres), one-channel PSF images (float TIFF, "
    ".npy, ...; paths relative to the JSON file) of one size, at most the capture's, finite, "
    "non-negative, centred at element (rows/2, cols/2) rounded down; each is normalised to sum "
    "1.\n"
    "The capture is read as grey (channels averaged). Outputs in -o DIR, written together: "
    "depth.tif (float32, metres), confidence.tif, all_in_focus.tif, depthmap.png (depth | "
    "confidence scaled to its maximum | colour bar: near dark at the top, far bright at the "
    "bottom), depthmap.json (also on stdout with --json). Progress per plane on stderr; Ctrl-C "
    "stops after the current plane and writes the sweep over the planes done.\n"
    "Examples:\n"
    "  pinmask depthmap cap.tif --mask m.mask.json --from 0.3m --to 2m\n"
    "  pinmask depthmap cap.tif --mask m.mask.json --from 1m --to inf --steps 8 -o dm --json\n"
    "  pinmask depthmap cap.tif --psf-stack measured/psf_stack.json --smooth 0";

void setup(CLI::App& app) {
    auto o = std::make_shared<DepthmapCommandOptions>();
    auto* cmd = app.add_subcommand(
        "depthmap",
        "Depth map, confidence and all-in-focus image from one capture (plane sweep over "
        "object distance).");
    cmd->footer(kFooter);
    cmd->add_option("capture", o->capture, "Capture image (TIFF, PNG, .npy, JPEG)")->required();
    cmd->add_option("--mask", o->mask,
                    "Mask file (*.mask.json) with its camera: the PSFs from its exact geometry");
    cmd->add_option("--psf-stack", o->psf_stack,
                    "Instead of --mask/--from/--to/--steps: PSFs at given distances (a "
                    "pinmask-psf-stack JSON file, or a folder holding psf_stack.json)");
    cmd->add_option("--from", o->from, "Nearest distance of the sweep (e.g. 0.3m), with --mask");
    cmd->add_option("--to", o->to, "Farthest distance of the sweep (e.g. 2m or inf), with --mask");
    auto* steps =
        cmd->add_option("--steps", o->steps,
                        "Planes of the sweep, equally spaced in 1/u (2..1000), with --mask")
            ->capture_default_str();
    cmd->add_option("--smooth", o->smooth,
                    "Smoothness weight of the depth labels (>= 0; 0: lowest-cost plane per "
                    "pixel). A one-plane step between neighbours costs the weight times the mean "
                    "depth of the pixels' cost wells, a larger jump twice that")
        ->capture_default_str();
    cmd->add_option("--nsr", o->nsr, "Wiener noise-to-signal ratio of every decode (> 0)")
        ->capture_default_str();
    cmd->add_option("--window", o->window,
                    "Side of the cost's box, px (odd, >= 3, at most the capture's smaller side)")
        ->capture_default_str();
    cmd->add_option("-o,--output-dir", o->output_dir,
                    "Folder for the outputs (created when missing)")
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "Print the summary as JSON on stdout");
    cmd->callback([o, steps] {
        o->steps_given = steps->count() > 0;
        run(*o);
    });
}

}  // namespace

void add_depthmap(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
