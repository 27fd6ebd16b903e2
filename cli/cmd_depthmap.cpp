// `pinmask depthmap CAPTURE --mask M [--from U1 --to U2 --steps N]` (or `--psf-stack STACK`): a
// depth map, its confidence and an all-in-focus image from one capture, by a plane sweep over
// object distance. Parses the flags, reads the inputs (the stack's format: io/psf_stack.hpp), runs
// decode/depthmap/depthmap_run and writes io/depthmap_json's files into -o DIR, together (their
// list: io/depthmap_json.hpp). Ctrl-C stops after the current plane and writes the sweep over the
// planes finished.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/options/decode_flags.hpp"
#include "cli/outputs/interrupt.hpp"
#include "cli/outputs/progress.hpp"
#include "core/files/output_set.hpp"
#include "core/image/image_io.hpp"
#include "core/units/units.hpp"
#include "decode/depthmap/depthmap_run.hpp"
#include "io/depthmap_json.hpp"
#include "io/mask_json.hpp"
#include "io/psf_stack.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

struct DepthmapCommandOptions {
    std::string capture;
    std::string mask;
    std::string psf_stack;
    std::string from, to;
    int steps = 0;
    bool steps_given = false;
    double smooth = DepthmapRequest{}.smooth;
    double nsr = DepthmapRequest{}.wiener_nsr;
    int window = DepthmapRequest{}.window;
    std::string background = "none";
    int downsample = 0;
    std::string output_dir = "depthmap_out";
    bool json = false;
};

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
    for (const fs::path& p : io::depthmap_file_paths(dir)) outputs.push_back({"-o", p, true});
    std::vector<NamedPath> inputs{{"CAPTURE", o.capture}, {"--mask", o.mask}};
    for (const fs::path& p : stack.files) inputs.push_back({"--psf-stack", p});
    plan_outputs(inputs, outputs);
    DepthmapRequest q;
    if (!o.mask.empty()) q.mask = io::read_mask_file(o.mask);
    q.capture = read_image(o.capture).image;
    q.capture_name = o.capture;
    q.mask_name = o.mask;
    q.psf_stack_name = o.psf_stack;
    if (o.psf_stack.empty()) {
        if (!o.from.empty()) q.from_m = parse_length_m(o.from, "--from");
        if (!o.to.empty()) q.to_m = parse_length_m(o.to, "--to", AllowInfinity::kYes);
        if (o.steps_given) q.steps = o.steps;
    } else {
        for (std::size_t k = 0; k < stack.psfs.size(); ++k)
            q.psf_stack.push_back({stack.distances_m[k], std::move(stack.psfs[k])});
    }
    q.capture_options.background = parse_background(o.background);
    q.capture_options.downsample = o.downsample;
    q.smooth = o.smooth;
    q.wiener_nsr = o.nsr;
    q.window = o.window;
    q.stop = &install_interrupt_flag();
    ProgressLine bar("pinmask depthmap");
    q.progress = [&](std::size_t done, std::size_t total) {
        if (done == 0) {
            bar.phase("plane sweep over " + std::to_string(total) + " distances");
            return;
        }
        bar.update(double(done) / double(total),
                   std::to_string(done) + "/" + std::to_string(total) + " planes");
    };
    DepthmapReport report = run_depthmap_request(std::move(q));
    bar.finish();
    io::write_depthmap_files(report, dir);
    const DepthmapResult& r = report.result;
    if (r.interrupted) {
        std::cerr << "depthmap: interrupted after " << r.distances_m.size() << " of "
                  << report.planes_planned << " planes: wrote the sweep over those\n";
    }
    if (o.json) {
        std::cout << io::depthmap_json(report).dump(2) << "\n";
        return;
    }
    for (const auto& p : io::depthmap_file_paths(dir)) std::cerr << "wrote " << p.string() << "\n";
    std::cout << io::depthmap_text(report);
}

constexpr const char* kFooter =
    "Plane sweep: for each of --steps distances from --from to --to (equally spaced in 1/u, the "
    "axis the pattern's scale follows), the capture is decoded (Wiener, scalar --nsr, the "
    "exact-geometry PSF at u over the whole frame, cyclic). Cost: the local energy (box of "
    "--window px) of the residual capture - PSF (*) estimate, which light from another distance "
    "raises. Labels: the plane per pixel that minimises the cost plus --smooth times a penalty "
    "on neighbouring pixels' planes (a one-plane step costs the weight times the mean depth of the "
    "pixels' cost wells, a larger jump twice that; semi-global dynamic programming along 8 "
    "paths; 0: the lowest-cost plane per pixel), refined by a parabola in 1/u; cost margin "
    "(median cost - chosen cost) / median cost, confidence the probability of a depth within one "
    "plane spacing it maps to (measured in docs/depth.md); the all-in-focus image takes each "
    "pixel from the decode at its plane. capture_depth_m: the lowest frame-mean cost (the whole "
    "capture as one plane); capture_evidence_depth_m: the lowest evidence (the capture's "
    "marginal likelihood under a 1/f^2 scene prior and white noise). Light from one point spreads "
    "over the whole PSF, so the map resolves "
    "depth only on regions about the PSF's size: measured accuracy in docs/depth.md.\n"
    "Defaults with --mask: --from/--to the design's usable object distances (as pinmask design "
    "prints), --steps one resolvable depth step apart (JSON `sweep`: what was chosen and the "
    "depth resolution). --background and --downsample prepare the capture with decode's corner "
    "patch and binning.\n"
    "--psf-stack STACK replaces --mask/--from/--to/--steps with measured or computed PSFs: a JSON "
    "file (or a folder holding psf_stack.json) {\"format\": \"pinmask-psf-stack\", "
    "\"version\": 1, \"planes\": [{\"object_distance_m\": 0.5, \"psf\": \"psf_0.5m.tif\"}, "
    "...]}: 2-1000 planes at distinct distances > 0 (metres), one-channel PSF images (float TIFF, "
    ".npy, ...; paths relative to the JSON file) of one size, at most the capture's, finite, "
    "non-negative, centred at element (rows/2, cols/2) rounded down; each is normalised to sum "
    "1.\n"
    "The capture is read as grey (channels averaged). Outputs in -o DIR, written together: "
    "depth.tif (float32, metres), confidence.tif, cost_margin.tif, all_in_focus.tif, depthmap.png "
    "(depth | "
    "confidence scaled to its maximum | colour bar: near dark at the top, far bright at the "
    "bottom), depthmap.json (also on stdout with --json). Progress per plane on stderr; Ctrl-C "
    "stops after the current plane and writes the sweep over the planes done.\n"
    "Examples:\n"
    "  pinmask depthmap cap.tif --mask m.mask.json   (the design's usable range)\n"
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
    cmd->add_option("--from", o->from,
                    "Nearest distance of the sweep (e.g. 0.3m), with --mask; default: the "
                    "design's nearest usable distance (as pinmask design prints)");
    cmd->add_option("--to", o->to,
                    "Farthest distance of the sweep (e.g. 2m or inf), with --mask; default: the "
                    "design's farthest usable distance");
    auto* steps =
        cmd->add_option("--steps", o->steps,
                        "Planes of the sweep, equally spaced in 1/u (2..1000), with --mask; "
                        "default: one resolvable depth step apart (the larger of one pixel of "
                        "pattern change and the Cramer-Rao FWHM), at most 64");
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
    cmd->add_option("--background", o->background,
                    "Off the capture before the sweep: none, corner (each image's own mean of "
                    "rows/cols 5..14: the capture's off the capture, each --psf-stack PSF's off "
                    "it, clipped at 0) or a number of counts")
        ->capture_default_str();
    cmd->add_option("--downsample", o->downsample,
                    "Rounds of 2x2 box averaging of the capture and the PSFs (0..12; a mask's "
                    "PSFs are drawn at the binned pixel pitch)")
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
