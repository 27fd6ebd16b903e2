// The `*.mask.json` codec. Layout (docs/design.md section 5; every key below is written, and every
// key is required on reading unless marked optional):
//   {"format": "pinmask-mask", "version": 1,
//    "pattern": {"n", "pinholes": [[row, col], ...], "tiles": [rows, cols], "min_spacing_cells"},
//    "optics": {"object_distance_m" (number or "inf"), "lens_focal_m" (number or "inf"),
//               "sensor_distance_m", "wavelength_m", "bandwidth_m" (optional, written when
//               not 0; not with psf.kernel.wavelengths), "pixel_pitch_m", "pinhole_m",
//               "sensor_px": [cols, rows]},
//    "psf": {"kernel": {"model", "measured_path" (optional), "wavelengths" (optional):
//                       [[wavelength_m, weight], ...]}, "pixels_per_cell"},
//    "provenance": {"seed", "generator", "family", "spacing_violations_allowed" (optional,
//                   default false), "scores" (optional, name -> number),
//                   "objective_figure" (optional, written when not empty: the scores key a
//                   search optimised),
//                   "geometry_hash" (optional; checked against the geometry when present)}}
// Output format: 2-space indent, keys in the order above, arrays of scalars on one line (one
// pinhole per line), numbers in nlohmann's shortest round-trip form, pinholes sorted.
#include "io/mask_json.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/files/atomic_file.hpp"
#include "core/files/input_file.hpp"
#include "core/files/output_set.hpp"
#include "core/limits/resource_limits.hpp"
#include "design/psf/kernel_model.hpp"
#include "io/json_strict.hpp"
#include "io/optics_json.hpp"

namespace pinmask::io {
namespace {

using namespace json_strict;

constexpr const char* kFormat = "pinmask-mask";
constexpr int kVersion = 1;
// Kernel models named by design/pattern/mask.hpp's KernelSpec (design/psf/kernel_model.hpp's
// table).
const std::vector<std::string> kKernelModels = name_list(kKernelModelNames);
// Reading holds the text twice (stream buffer and string), the pinholes (8 bytes per ~10 bytes
// of text, streamed out of the parser) and their sorted copy: about this many bytes per byte of
// text. Used to refuse files that cannot be held.
constexpr double kParsedBytesPerTextByte = 4.0;

// `streamed`: the pinholes already taken out of the tree by parse_strict (nullptr: read them
// from the tree).
Pattern read_pattern(const Json& j, const std::vector<Cell>* streamed) {
    ObjectReader r(j, "pattern", {"n", "pinholes", "tiles", "min_spacing_cells"});
    r.reject_unknown();
    Pattern p;
    p.n = read_int(r.required("n"), r.path("n"));
    if (p.n < 1 || p.n > kMaxGrid) {
        fail(r.path("n"),
             std::to_string(p.n) + " must be between 1 and " + std::to_string(kMaxGrid));
    }
    const Json& holes = r.required("pinholes");
    if (!holes.is_array()) {
        fail(r.path("pinholes"),
             std::string("must be an array of [row, col], got ") + holes.type_name());
    }
    if (streamed) {
        p.pinholes = *streamed;
    } else {
        p.pinholes.reserve(holes.size());
        for (std::size_t i = 0; i < holes.size(); ++i) {
            const auto [row, col] =
                read_int_pair(holes[i], indexed(r.path("pinholes"), i), "[row, col]");
            p.pinholes.push_back({row, col});
        }
    }
    const auto [tr, tc] = read_int_pair(r.required("tiles"), r.path("tiles"), "[rows, cols]");
    p.tiles_rows = tr;
    p.tiles_cols = tc;
    p.min_spacing_cells = read_number(r.required("min_spacing_cells"), r.path("min_spacing_cells"));
    return p;
}

KernelSpec read_kernel(const Json& j) {
    ObjectReader r(j, "psf.kernel", {"model", "measured_path", "wavelengths"});
    r.reject_unknown();
    KernelSpec k;
    k.model = read_string(r.required("model"), r.path("model"));
    if (std::find(kKernelModels.begin(), kKernelModels.end(), k.model) == kKernelModels.end()) {
        std::string list;
        for (const auto& m : kKernelModels) list += (list.empty() ? "" : ", ") + m;
        fail(r.path("model"), "\"" + k.model + "\" is not a kernel model (one of: " + list + ")");
    }
    if (const Json* mp = r.optional("measured_path")) {
        k.measured_path = read_string(*mp, r.path("measured_path"));
        if (k.model != "measured") {
            fail(r.path("measured_path"),
                 "only used with model \"measured\" (model is \"" + k.model + "\")");
        }
    }
    if (k.model == "measured" && k.measured_path.empty()) {
        fail(r.path("measured_path"), "model \"measured\" needs a non-empty measured_path");
    }
    if (const Json* wl = r.optional("wavelengths")) {
        const std::string path = r.path("wavelengths");
        if (!wl->is_array() || wl->empty()) {
            fail(path, "must be a non-empty array of [wavelength_m, weight]");
        }
        double total = 0.0;
        for (std::size_t i = 0; i < wl->size(); ++i) {
            const Json& e = (*wl)[i];
            const std::string ep = indexed(path, i);
            if (!e.is_array() || e.size() != 2) fail(ep, "must be [wavelength_m, weight]");
            const double w = read_number(e[0], indexed(ep, 0));
            const double weight = read_number(e[1], indexed(ep, 1));
            if (w <= 0.0) fail(indexed(ep, 0), "wavelength must be > 0");
            if (weight < 0.0) fail(indexed(ep, 1), "weight must be >= 0");
            total += weight;
            k.wavelengths.emplace_back(w, weight);
        }
        if (total <= 0.0) fail(path, "weights must not all be zero");
    }
    return k;
}

PsfSpec read_psf(const Json& j) {
    ObjectReader r(j, "psf", {"kernel", "pixels_per_cell"});
    r.reject_unknown();
    PsfSpec s;
    s.kernel = read_kernel(r.required("kernel"));
    s.pixels_per_cell = read_int(r.required("pixels_per_cell"), r.path("pixels_per_cell"));
    if (s.pixels_per_cell < 1) {
        fail(r.path("pixels_per_cell"), std::to_string(s.pixels_per_cell) + " must be >= 1");
    }
    return s;
}

// Returns the provenance and, through `hash`, the recorded geometry hash ("" when absent).
Provenance read_provenance(const Json& j, std::string& hash) {
    ObjectReader r(j, "provenance",
                   {"seed", "generator", "family", "spacing_violations_allowed", "scores",
                    "objective_figure", "geometry_hash"});
    r.reject_unknown();
    Provenance p;
    const Json& seed = r.required("seed");
    if (!seed.is_number_unsigned()) {
        fail(r.path("seed"), "must be a non-negative integer, got " + seed.dump());
    }
    p.seed = seed.get<std::uint64_t>();
    p.generator = read_string(r.required("generator"), r.path("generator"));
    p.family = read_string(r.required("family"), r.path("family"));
    if (const Json* a = r.optional("spacing_violations_allowed")) {
        p.spacing_violations_allowed = read_bool(*a, r.path("spacing_violations_allowed"));
    }
    if (const Json* s = r.optional("scores")) {
        if (!s->is_object()) fail(r.path("scores"), "must be an object of name -> number");
        for (const auto& item : s->items()) {
            p.scores[item.key()] = read_number(item.value(), r.path("scores") + "." + item.key());
        }
    }
    if (const Json* f = r.optional("objective_figure")) {
        p.objective_figure = read_string(*f, r.path("objective_figure"));
    }
    hash.clear();
    if (const Json* h = r.optional("geometry_hash")) {
        hash = read_string(*h, r.path("geometry_hash"));
    }
    return p;
}

// The file's JSON. Without pinholes (the array left empty), for the writer, which prints them
// directly: a million pinholes as JSON nodes would cost seconds and hundreds of MB.
template <class J>
J build_json(const Mask& m, bool with_pinholes = true) {
    J j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    J pattern;
    pattern["n"] = m.pattern.n;
    J holes = J::array();
    if (with_pinholes) {
        for (const Cell& c : sorted_pinholes(m.pattern)) holes.push_back(J::array({c.row, c.col}));
    }
    pattern["pinholes"] = std::move(holes);
    pattern["tiles"] = J::array({m.pattern.tiles_rows, m.pattern.tiles_cols});
    pattern["min_spacing_cells"] = m.pattern.min_spacing_cells;
    j["pattern"] = std::move(pattern);

    j["optics"] = optics_to_json<J>(m.camera);

    J kernel;
    kernel["model"] = m.psf.kernel.model;
    if (!m.psf.kernel.measured_path.empty()) kernel["measured_path"] = m.psf.kernel.measured_path;
    if (!m.psf.kernel.wavelengths.empty()) {
        J wl = J::array();
        for (const auto& [w, weight] : m.psf.kernel.wavelengths)
            wl.push_back(J::array({w, weight}));
        kernel["wavelengths"] = std::move(wl);
    }
    J psf;
    psf["kernel"] = std::move(kernel);
    psf["pixels_per_cell"] = m.psf.pixels_per_cell;
    j["psf"] = std::move(psf);

    const Provenance& p = m.provenance;
    J prov;
    prov["seed"] = p.seed;
    prov["generator"] = p.generator;
    prov["family"] = p.family;
    prov["spacing_violations_allowed"] = p.spacing_violations_allowed;
    J scores = J::object();
    for (const auto& [name, value] : p.scores) scores[name] = value;
    prov["scores"] = std::move(scores);
    if (!p.objective_figure.empty()) prov["objective_figure"] = p.objective_figure;
    prov["geometry_hash"] = geometry_hash(m);
    j["provenance"] = std::move(prov);
    return j;
}

constexpr const char* kPinholesPath = "pattern.pinholes";

Mask from_json(const Json& j, const MaskReadOptions& options, const std::vector<Cell>* streamed) {
    ObjectReader top(j, "", {"format", "version", "pattern", "optics", "psf", "provenance"});
    const Json& format = top.required("format");
    if (!format.is_string() || format.get<std::string>() != kFormat) {
        fail("format",
             format.dump() + " is not \"" + std::string(kFormat) + "\" (not a pinmask mask file)");
    }
    const Json& version = top.required("version");
    if (!version.is_number_integer() || version.get<std::int64_t>() != kVersion) {
        fail("version", version.dump() + " is not supported (this build reads version " +
                            std::to_string(kVersion) + ")");
    }
    top.reject_unknown();
    Mask m;
    m.pattern = read_pattern(top.required("pattern"), streamed);
    m.camera = optics_from_json(top.required("optics"));
    m.psf = read_psf(top.required("psf"));
    if (m.camera.bandwidth_m > 0.0 && !m.psf.kernel.wavelengths.empty()) {
        fail("optics.bandwidth_m",
             "and psf.kernel.wavelengths both give the light's spectrum: keep one of them (the "
             "band is sampled as docs/commands.md says; the list is used as written)");
    }
    std::string recorded_hash;
    m.provenance = read_provenance(top.required("provenance"), recorded_hash);
    validate(m.pattern,
             options.allow_spacing_violations || m.provenance.spacing_violations_allowed);
    m.pattern.pinholes = sorted_pinholes(m.pattern);
    if (!recorded_hash.empty()) {
        const std::string actual = geometry_hash(m);
        if (recorded_hash != actual) {
            fail("provenance.geometry_hash",
                 "\"" + recorded_hash + "\" does not match the geometry in the file (\"" + actual +
                     "\"): the pattern or pinhole size was edited without updating the hash; "
                     "remove the key to accept the edit");
        }
    }
    return m;
}

}  // namespace

Mask mask_from_json(const Json& j, const MaskReadOptions& options) {
    return from_json(j, options, nullptr);
}

Json mask_to_json(const Mask& mask) { return build_json<Json>(mask); }

std::string mask_file_text(const Mask& mask) {
    // Nothing is written that could not be read back: everything but the pinholes goes through
    // the reader, the pinholes through the same pattern validation the reader runs.
    const bool allow = mask.provenance.spacing_violations_allowed;
    Json check = build_json<Json>(mask, /*with_pinholes=*/false);
    check["provenance"].erase("geometry_hash");
    MaskReadOptions opts;
    opts.allow_spacing_violations = allow;
    mask_from_json(check, opts);
    validate(mask.pattern, allow);
    const std::vector<Cell> cells = sorted_pinholes(mask.pattern);
    const auto write_pinholes = [&cells](std::string& out, int indent) {
        if (cells.empty()) {
            out += "[]";
            return;
        }
        const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
        out += "[\n";
        char buf[32];
        for (std::size_t i = 0; i < cells.size(); ++i) {
            std::snprintf(buf, sizeof buf, "[%d, %d]", cells[i].row, cells[i].col);
            if (i) out += ",\n";
            out += pad;
            out += buf;
        }
        out += '\n';
        out.append(static_cast<std::size_t>(indent), ' ');
        out += ']';
    };
    return pretty(build_json<OrderedJson>(mask, /*with_pinholes=*/false), kPinholesPath,
                  write_pinholes) +
           "\n";
}

bool is_mask_file(const std::filesystem::path& path) {
    if (path.extension() == ".json") return true;
    if (input_file_problem(path)) return false;  // the reader that follows says why
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
    }
    return in && c == '{';
}

Mask read_mask_file(const std::filesystem::path& path, const MaskReadOptions& options) {
    const std::string name = path.string();
    if (const auto problem = input_file_problem(path))
        throw InvalidInput(name + ": cannot read mask file (" + *problem + ")");
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw InvalidInput(name + ": cannot read mask file (" + ec.message() + ")");
    protect_input(path);  // no output of this run may replace it (core/files/output_set)
    check_memory(static_cast<double>(size) * kParsedBytesPerTextByte, "parsing mask file " + name);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InvalidInput(name + ": cannot open mask file for reading");
    std::ostringstream buf;
    buf << in.rdbuf();
    Json j;
    std::vector<Cell> pinholes;
    try {
        j = parse_strict(buf.str(), kPinholesPath, [&pinholes](const Json& e, std::size_t i) {
            int rc[2];
            if (e.is_array() && e.size() == 2 && small_int(e[0], rc[0]) && small_int(e[1], rc[1])) {
                pinholes.push_back({rc[0], rc[1]});
            } else {  // throws with the key path and the rule
                read_int_pair(e, indexed(kPinholesPath, i), "[row, col]");
            }
        });
    } catch (const Json::parse_error& e) {
        throw InvalidInput(name + ": invalid JSON (byte " + std::to_string(e.byte) +
                           "): " + json_error_words(e));
    } catch (const Json::exception& e) {  // e.g. out_of_range.406: a number too large
        throw InvalidInput(name + ": invalid JSON: " + json_error_words(e));
    } catch (const InvalidInput& e) {
        throw InvalidInput(name + ": " + e.what());
    }
    try {
        return from_json(j, options, &pinholes);
    } catch (const InvalidInput& e) {
        throw InvalidInput(name + ": " + e.what());
    }
}

void write_mask_file(const std::filesystem::path& path, const Mask& mask) {
    std::string text;
    try {
        text = mask_file_text(mask);
    } catch (const InvalidInput& e) {
        throw InvalidInput("refusing to write " + path.string() + ": " + e.what());
    }
    write_bytes_atomic(path, text);
}

}  // namespace pinmask::io
