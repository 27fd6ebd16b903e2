// Patterns and masks: the pattern families (design/pattern/families, random_sparse, mura), the mask
// file codec (io/mask_json), the geometry hash. generate() follows `pinmask generate` step by
// step (same checks, same messages, same file bytes for the same seed).
#include <optional>
#include <random>
#include <sstream>

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "core/version.hpp"
#include "design/optics/optics.hpp"
#include "design/pattern/exclusion_grid.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/generate_pattern.hpp"
#include "design/pattern/mask.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/pattern.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf_settings.hpp"
#include "io/json_strict.hpp"
#include "io/mask_json.hpp"
#include "python/common.hpp"

namespace pinmask::python {

namespace {

constexpr const char* kGenerator = PINMASK_GENERATOR("generate");

py::list cells_to_list(const std::vector<Cell>& cells) {
    py::list l;
    for (const Cell& c : cells) l.append(py::make_tuple(c.row, c.col));
    return l;
}

std::vector<Cell> cells_from(const py::iterable& it) {
    std::vector<Cell> cells;
    for (const py::handle& h : it) {
        const auto rc = h.cast<std::pair<int, int>>();
        cells.push_back({rc.first, rc.second});
    }
    return cells;
}

}  // namespace

void bind_mask(py::module_& m) {
    py::class_<Pattern>(m, "Pattern",
                        "A cyclic pattern: an n x n torus of cells (cell side = pinhole side d), "
                        "K open cells (pinholes), tiled tiles_rows x tiles_cols times on the "
                        "mask; pinhole centres at least min_spacing_cells cell sides apart on "
                        "the torus.")
        .def(py::init([](int n, const py::iterable& pinholes, int tiles_rows, int tiles_cols,
                         double min_spacing_cells) {
                 Pattern p;
                 p.n = n;
                 p.pinholes = cells_from(pinholes);
                 p.tiles_rows = tiles_rows;
                 p.tiles_cols = tiles_cols;
                 p.min_spacing_cells = min_spacing_cells;
                 return p;
             }),
             py::arg("n") = 16, py::arg("pinholes") = py::list(), py::arg("tiles_rows") = 2,
             py::arg("tiles_cols") = 2, py::arg("min_spacing_cells") = 2.0)
        .def_readwrite("n", &Pattern::n, "cells per side")
        .def_property(
            "pinholes", [](const Pattern& p) { return cells_to_list(p.pinholes); },
            [](Pattern& p, const py::iterable& it) { p.pinholes = cells_from(it); },
            "open cells as a list of (row, col), 0 <= row, col < n")
        .def_readwrite("tiles_rows", &Pattern::tiles_rows)
        .def_readwrite("tiles_cols", &Pattern::tiles_cols)
        .def_readwrite("min_spacing_cells", &Pattern::min_spacing_cells,
                       "spacing rule, in cell sides (Euclidean, on the torus)")
        .def(
            "occupancy",
            [](const Pattern& p) {
                const auto occ = occupancy(p);
                py::array_t<std::uint8_t> a({p.n, p.n});
                std::copy(occ.begin(), occ.end(), a.mutable_data());
                return a;
            },
            "The n x n 0/1 occupancy as a uint8 array (1 = pinhole).")
        .def(
            "spacing_violations",
            [](const Pattern& p) {
                py::list l;
                for (const auto& v : spacing_violations(p))
                    l.append(py::make_tuple(py::make_tuple(v.a.row, v.a.col),
                                            py::make_tuple(v.b.row, v.b.col), v.distance_cells));
                return l;
            },
            "Pairs closer than min_spacing_cells: [((row, col), (row, col), distance_cells)].")
        .def(
            "validate",
            [](const Pattern& p, bool allow_spacing_violations) {
                validate(p, allow_spacing_violations);
            },
            py::arg("allow_spacing_violations") = false,
            "ValueError naming the problem (grid, tiles, duplicates, the spacing rule).");

    py::class_<Mask>(m, "Mask",
                     "A mask: the pattern, the camera it is designed for, how its PSF is "
                     "synthesised (kernel model, pixels per cell) and its provenance; the "
                     "in-memory form of *.mask.json.")
        .def(py::init<>())
        .def_readwrite("pattern", &Mask::pattern)
        .def_readwrite("camera", &Mask::camera)
        .def_property(
            "pixels_per_cell", [](const Mask& k) { return k.psf.pixels_per_cell; },
            [](Mask& k, int v) { k.psf.pixels_per_cell = v; },
            "image-plane cell pitch in sensor pixels (integer)")
        .def_property(
            "kernel", [](const Mask& k) { return k.psf.kernel.model; },
            [](Mask& k, const std::string& v) { k.psf.kernel.model = v; },
            "kernel model: one of kernel_models()")
        .def_property(
            "kernel_path", [](const Mask& k) { return k.psf.kernel.measured_path; },
            [](Mask& k, const std::string& v) { k.psf.kernel.measured_path = v; },
            "kernel image of the measured model")
        .def_property(
            "wavelengths", [](const Mask& k) { return k.psf.kernel.wavelengths; },
            [](Mask& k, const std::vector<std::pair<double, double>>& v) {
                k.psf.kernel.wavelengths = v;
            },
            "polychromatic kernel: [(wavelength_m, weight)]; empty = the camera's wavelength")
        .def_property(
            "seed", [](const Mask& k) { return k.provenance.seed; },
            [](Mask& k, std::uint64_t v) { k.provenance.seed = v; })
        .def_property(
            "generator", [](const Mask& k) { return k.provenance.generator; },
            [](Mask& k, const std::string& v) { k.provenance.generator = v; })
        .def_property(
            "family", [](const Mask& k) { return k.provenance.family; },
            [](Mask& k, const std::string& v) { k.provenance.family = v; })
        .def_property(
            "spacing_violations_allowed",
            [](const Mask& k) { return k.provenance.spacing_violations_allowed; },
            [](Mask& k, bool v) { k.provenance.spacing_violations_allowed = v; })
        .def_property(
            "scores", [](const Mask& k) { return k.provenance.scores; },
            [](Mask& k, const std::map<std::string, double>& v) { k.provenance.scores = v; },
            "metric name -> value (names carry units)")
        .def_property(
            "objective_figure", [](const Mask& k) { return k.provenance.objective_figure; },
            [](Mask& k, const std::string& v) { k.provenance.objective_figure = v; },
            "the scores key of the figure a search optimised ('' for a mask no search made)")
        .def("geometry_hash", &geometry_hash,
             "16 hex digits (FNV-1a 64) of n, sorted pinholes, tiles, pinhole side (nm) and "
             "spacing: identical geometry, identical hash.")
        .def("to_json", &io::mask_file_text,
             "The exact text `save_mask` writes (and `pinmask generate` writes for this mask).")
        .def(
            "save",
            [](const Mask& k, const std::filesystem::path& path) { io::write_mask_file(path, k); },
            py::arg("path"),
            "Writes the mask file atomically (same bytes as the CLI for the same mask).")
        .def("__repr__", [](const Mask& k) {
            return "<pinmask.Mask n=" + std::to_string(k.pattern.n) +
                   " holes=" + std::to_string(k.pattern.pinholes.size()) +
                   " hash=" + geometry_hash(k) + ">";
        });

    m.def(
        "load_mask",
        [](const std::filesystem::path& path, bool allow_spacing_violations) {
            io::MaskReadOptions o;
            o.allow_spacing_violations = allow_spacing_violations;
            return io::read_mask_file(path, o);
        },
        py::arg("path"), py::arg("allow_spacing_violations") = false,
        "Reads and validates a *.mask.json (ValueError naming the file, key and rule).");
    m.def(
        "save_mask",
        [](const Mask& mask, const std::filesystem::path& path) {
            io::write_mask_file(path, mask);
        },
        py::arg("mask"), py::arg("path"), "Writes a *.mask.json atomically.");
    m.def(
        "mask_from_json",
        [](const std::string& text, bool allow_spacing_violations) {
            io::MaskReadOptions o;
            o.allow_spacing_violations = allow_spacing_violations;
            nlohmann::json j;
            try {  // the file reader's parser: repeated keys refused, syntax errors named
                j = io::json_strict::parse_strict(text);
            } catch (const nlohmann::json::exception& e) {
                throw InvalidInput(std::string("mask JSON: ") + e.what());
            }
            return io::mask_from_json(j, o);
        },
        py::arg("text"), py::arg("allow_spacing_violations") = false,
        "A mask from the text of a *.mask.json.");

    m.def(
        "generate",
        [](const std::string& family, std::optional<int> grid, std::optional<int> holes,
           std::optional<int> tiles, std::optional<double> spacing, std::uint64_t seed,
           int attempts, bool allow_violations, const std::optional<Camera>& camera,
           const std::string& kernel, const std::string& kernel_path,
           std::optional<int> pixels_per_cell) {
            const Family fam = parse_family(family);
            // `pinmask generate`'s order: options, camera, PSF, PSF size, pattern
            // (design/pattern/generate_pattern: the one pattern pipeline, same checks and
            // messages).
            GeneratePatternOptions go;
            go.family = fam;
            go.grid = grid.value_or(go.grid);
            go.holes = holes.value_or(go.holes);
            go.tiles = tiles.value_or(go.tiles);
            go.spacing = spacing.value_or(go.spacing);
            go.grid_given = grid.has_value();
            go.holes_given = holes.has_value();
            go.tiles_given = tiles.has_value();
            go.spacing_given = spacing.has_value();
            go.seed = seed;
            go.attempts = attempts;
            go.allow_violations = allow_violations;
            go.validate();
            Mask mk;
            mk.camera = camera.value_or(paper_camera());
            validate(mk.camera);
            PsfSettings po;
            po.kernel = kernel;
            po.kernel_path = kernel_path;
            po.pixels_per_cell = pixels_per_cell;
            parse_kernel_model(kernel, field_ref("kernel"));
            mk.psf = resolve_psf_spec(po, mk.camera);
            check_period_psf_size(mk.psf.pixels_per_cell, go.grid, pixels_per_cell.has_value());
            go.pinhole_m = mk.camera.pinhole_m;  // the rule on the 1 nm grid, as the CLI
            const GeneratedPattern gen = generate_pattern(go);
            const std::size_t violations = gen.spacing_violations;
            mk.pattern = gen.pattern;
            mk.provenance.seed = fam == Family::kMura ? 0 : seed;
            mk.provenance.generator = kGenerator;
            mk.provenance.family = family_name(fam);
            mk.provenance.spacing_violations_allowed = violations > 0;
            return mk;
        },
        py::arg("family") = "random", py::arg("grid") = py::none(), py::arg("holes") = py::none(),
        py::arg("tiles") = py::none(), py::arg("spacing") = py::none(), py::arg("seed") = 1,
        py::arg("attempts") = 20, py::arg("allow_violations") = false,
        py::arg("camera") = py::none(), py::arg("kernel") = "auto", py::arg("kernel_path") = "",
        py::arg("pixels_per_cell") = py::none(),
        "A pattern of one family (random | paper | mura) for a camera, as `pinmask generate`: "
        "grid n (default 16), holes K (20), tiles per side (2), spacing in cells (2.0); None "
        "means 'not given' (the paper and mura families refuse other values). seed of the "
        "random families; attempts = restarts of random placement; pixels_per_cell default: the "
        "nearest integer to d |1 - f/f'| / w. Same seed and arguments: the same mask file "
        "bytes as the CLI.");
}

}  // namespace pinmask::python
