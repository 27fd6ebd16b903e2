// `pinmask generate`: a pattern from one family (random | paper | mura) for a camera -> a mask
// file (*.mask.json). The mask file records the whole resolved configuration (geometry, optics,
// PSF settings, seed, generator), so no separate configuration file is written.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "cli/commands.hpp"
#include "cli/options/camera_options.hpp"
#include "cli/options/psf_options.hpp"
#include "core/errors/error.hpp"
#include "core/files/output_set.hpp"
#include "core/units/units.hpp"
#include "core/version.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/optics.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/generate_pattern.hpp"
#include "design/pattern/mask.hpp"
#include "io/mask_json.hpp"

namespace pinmask::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kGenerator = PINMASK_GENERATOR("generate");

struct GenerateOptions {
    std::string family = "random";
    GeometryOptions geometry;
    std::uint64_t seed = 1;
    int attempts = 20;
    bool allow_violations = false;
    CameraOptions camera;
    PsfOptions psf;
    std::string output;
    bool json = false;
};

void run(const GenerateOptions& o, const CLI::App& cmd) {
    const Family family = parse_family(o.family);
    const fs::path out_dir = fs::path(o.output).parent_path();
    if (!out_dir.empty() && !fs::is_directory(out_dir)) {
        throw invalid_field("-o", o.output, "the output directory does not exist");
    }
    GeneratePatternOptions go;
    go.family = family;
    go.grid = o.geometry.grid;
    go.holes = o.geometry.holes;
    go.tiles = o.geometry.tiles;
    go.spacing = o.geometry.spacing;
    go.grid_given = cmd.count("--grid") > 0;
    go.holes_given = cmd.count("--holes") > 0;
    go.tiles_given = cmd.count("--tiles") > 0;
    go.spacing_given = cmd.count("--spacing") > 0;
    go.seed = o.seed;
    go.attempts = o.attempts;
    go.allow_violations = o.allow_violations;
    go.validate();
    plan_outputs({}, {{"-o", o.output}});

    Mask m;
    m.camera = resolve_camera(o.camera);
    go.pinhole_m = m.camera.pinhole_m;  // the rule on the 1 nm grid, as export evaluates it
    const double design_ppc = design_pixels_per_cell(m.camera);
    m.psf = resolve_psf_spec(o.psf, m.camera);
    check_period_psf_size(m.psf.pixels_per_cell, o.geometry.grid,
                          o.psf.pixels_per_cell.has_value());
    const GeneratedPattern gen = generate_pattern(go);
    const std::size_t violations = gen.spacing_violations;
    m.pattern = gen.pattern;
    // A MURA does not depend on the seed: recording 0 keeps its file independent of --seed.
    m.provenance.seed = family == Family::kMura ? 0 : o.seed;
    m.provenance.generator = kGenerator;
    m.provenance.family = family_name(family);
    m.provenance.spacing_violations_allowed = violations > 0;  // only reached when allowed
    io::write_mask_file(o.output, m);

    const std::string hash = geometry_hash(m);
    const std::size_t k = m.pattern.pinholes.size();
    if (o.json) {
        const nlohmann::ordered_json j = {
            {"path", o.output},
            {"geometry_hash", hash},
            {"family", m.provenance.family},
            {"seed", m.provenance.seed},
            {"n", m.pattern.n},
            {"holes", k},
            {"tiles", {m.pattern.tiles_rows, m.pattern.tiles_cols}},
            {"min_spacing_cells", m.pattern.min_spacing_cells},
            {"spacing_limit_m", gen.grid.limit_nm * 1e-9},
            {"closest_pair_m", std::isfinite(gen.grid.closest_nm)
                                   ? nlohmann::ordered_json(gen.grid.closest_nm * 1e-9)
                                   : nlohmann::ordered_json(nullptr)},
            {"fab_grid_m", double(gen.grid.grid_nm) * 1e-9},
            {"spacing_violations", violations},
            {"pinhole_m", m.camera.pinhole_m},
            {"pixels_per_cell", m.psf.pixels_per_cell},
            {"pixels_per_cell_design", design_ppc},
            {"kernel", m.psf.kernel.model}};
        std::cout << j.dump() << "\n";
        return;
    }
    const int n = m.pattern.n;
    std::ostringstream s;
    s << std::fixed;
    s << "wrote " << o.output << "\n";
    s << "  family         " << m.provenance.family;
    if (family != Family::kMura) s << " (seed " << o.seed << ")";
    s << "\n  pattern        " << n << " x " << n << " cells, " << k << " pinholes ("
      << std::setprecision(1) << 100.0 * static_cast<double>(k) / (double(n) * n)
      << " % open), tiles " << m.pattern.tiles_rows << " x " << m.pattern.tiles_cols << "\n";
    s << std::defaultfloat << "  spacing        >= " << m.pattern.min_spacing_cells
      << " cells on the torus: "
      << (violations == 0 ? std::string("met")
                          : std::to_string(violations) + " pair(s) closer (allowed)")
      << "\n                 "
      << spacing_rule_text(m.pattern.min_spacing_cells, gen.grid.pitch_nm, gen.grid.grid_nm)
      << (std::isfinite(gen.grid.closest_nm) ? "; closest " + um_text(gen.grid.closest_nm)
                                             : std::string("; no pair within reach"))
      << "\n";
    s << "  pinhole        " << format_length(m.camera.pinhole_m) << ", mask "
      << n * m.pattern.tiles_cols << " x " << n * m.pattern.tiles_rows
      << " cells = " << format_length(n * m.pattern.tiles_cols * m.camera.pinhole_m) << " x "
      << format_length(n * m.pattern.tiles_rows * m.camera.pinhole_m) << "\n";
    s << "  pixels/cell    " << m.psf.pixels_per_cell << " (design value " << std::fixed
      << std::setprecision(2) << design_ppc << " for a distant object)\n"
      << std::defaultfloat;
    s << "  kernel         " << m.psf.kernel.model << "\n";
    s << "  geometry hash  " << hash << "\n";
    std::cout << s.str();
}

constexpr const char* kFooter =
    "The mask file records the whole resolved configuration (pattern, optics, PSF settings, "
    "seed, generator, geometry hash), so no separate configuration file is written.\n"
    "Families: random = K pinholes, each drawn uniformly among the cells still free under the "
    "spacing rule (restarted up to --attempts times; a request above the proven packing bound "
    "is refused at once with the bound, a verified lattice count and what the random search "
    "reached). paper = random with the paper's geometry (16 x 16, K 20, 2 x 2 tiles, spacing "
    "2). mura = modified uniformly redundant array of prime order p = 4m + 1 given by --grid "
    "(Gottesman & Fenimore 1989; row 0 closed, column 0 open); it breaks any spacing above 1, "
    "so it needs --allow-violations (or --spacing 1). URAs are rectangular and not offered.\n"
    "Example: pinmask generate --family random --grid 16 --holes 20 --spacing 2 --tiles 2 "
    "--seed 7 -o m.mask.json";

void setup(CLI::App& app) {
    auto o = std::make_shared<GenerateOptions>();
    auto* cmd = app.add_subcommand(
        "generate",
        "Generate a pattern (random | paper | mura) for a camera and write it as a "
        "mask file (*.mask.json).");
    cmd->footer(kFooter);
    cmd->add_option("--family", o->family,
                    "Pattern family: random | paper | mura (ura is not available: not square)")
        ->capture_default_str();
    add_geometry_options(*cmd, o->geometry);
    cmd->add_option("--seed", o->seed,
                    "Seed of the random generator (random, paper); recorded in the file (mura: "
                    "ignored, recorded as 0)")
        ->capture_default_str();
    cmd->add_option("--attempts", o->attempts,
                    "random/paper: restarts when random sequential placement runs out of free "
                    "cells before K")
        ->capture_default_str();
    cmd->add_flag("--allow-violations", o->allow_violations,
                  "Write a pattern that breaks the spacing rule (mura); the file then records "
                  "spacing_violations_allowed = true");
    add_camera_options(*cmd, o->camera);
    add_psf_options(*cmd, o->psf);
    cmd->add_option("-o,--output", o->output, "Output mask file (*.mask.json), written atomically")
        ->required();
    cmd->add_flag("--json", o->json,
                  "Print {path, geometry_hash, family, seed, n, holes, tiles, min_spacing_cells, "
                  "spacing_violations, pinhole_m, pixels_per_cell, pixels_per_cell_design, "
                  "kernel} on stdout instead of the summary");
    cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace

void add_generate(CLI::App& app) { setup(app); }
}  // namespace pinmask::cli
