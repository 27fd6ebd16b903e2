#include "bench/export_bench.hpp"

#include <time.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <numeric>
#include <random>

#include "core/errors/error.hpp"
#include "design/pattern/mask.hpp"
#include "export/formats/dxf_writer.hpp"
#include "export/formats/gds_writer.hpp"
#include "export/formats/gerber_writer.hpp"
#include "export/formats/pdf_writer.hpp"
#include "export/formats/png_preview.hpp"
#include "export/formats/read_any.hpp"
#include "export/formats/svg_writer.hpp"
#include "export/formats/write_any.hpp"
#include "export/layout/geometry.hpp"
#include "export/pipeline/read_back.hpp"

namespace pinmask {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Timing {
    double wall = 1e300;
    double cpu = 1e300;
};

double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

Timing time_min(int repeat, const std::function<void()>& f) {
    Timing best;
    for (int i = 0; i < repeat; ++i) {
        const auto t0 = Clock::now();
        const double c0 = thread_cpu_seconds();
        f();
        best.cpu = std::min(best.cpu, thread_cpu_seconds() - c0);
        best.wall = std::min(best.wall, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return best;
}

ExportBenchRecord record(std::string stage, Timing t, std::size_t bytes, std::string reference,
                         Timing ref) {
    return {std::move(stage),     t.wall,   t.cpu,   bytes,
            std::move(reference), ref.wall, ref.cpu, ref.cpu > 0 ? t.cpu / ref.cpu : 0.0};
}

void fwrite_file(const fs::path& p, const std::string& bytes) {
    std::FILE* f = std::fopen(p.c_str(), "wb");
    if (!f) throw RuntimeFailure("cannot write " + p.string());
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (std::fclose(f) != 0 || !ok) throw RuntimeFailure("failed writing " + p.string());
}

// The jittered lattice on an n x n pattern, tiled `tiles` x `tiles`.
Mask bench_mask(const ExportBenchOptions& o, int n, int tiles) {
    Mask m;
    m.camera.pinhole_m = o.pinhole_m;
    m.pattern.n = n;
    m.pattern.tiles_rows = m.pattern.tiles_cols = tiles;
    m.pattern.min_spacing_cells = 2.0;
    std::mt19937_64 rng(o.seed);
    std::bernoulli_distribution keep(0.86), half(0.5);
    for (int r = 0; r + 2 < n; r += 3)
        for (int c = 0; c + 2 < n; c += 3)
            if (keep(rng)) m.pattern.pinholes.push_back({r + half(rng), c + half(rng)});
    return m;
}

Mask bench_mask(const ExportBenchOptions& o) { return bench_mask(o, o.n, 1); }

// Uniformly random cells (no structure for a dictionary to share): as many pinholes as the
// jittered lattice, any positions (spacing rule off; drawn at half the cell so neighbours stay
// separate polygons).
Mask uniform_mask(const ExportBenchOptions& o, std::size_t count) {
    Mask m;
    m.camera.pinhole_m = o.pinhole_m;
    m.pattern.n = o.n;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 1;
    m.pattern.min_spacing_cells = 0.0;
    m.provenance.spacing_violations_allowed = true;
    std::mt19937_64 rng(o.seed);
    std::vector<int> cells(std::size_t(o.n) * std::size_t(o.n));
    std::iota(cells.begin(), cells.end(), 0);
    for (std::size_t k = 0; k < count && k < cells.size(); ++k) {  // partial Fisher-Yates
        std::uniform_int_distribution<std::size_t> pick(k, cells.size() - 1);
        std::swap(cells[k], cells[pick(rng)]);
        m.pattern.pinholes.push_back({cells[k] / o.n, cells[k] % o.n});
    }
    return m;
}

// File sizes of one mask: flat GDSII, hierarchical GDSII and OASIS, each read back and checked
// equal to the layout (so a small file is never a wrong one).
ExportSizeRecord sizes_of(const std::string& name, const Mask& mask, const LayoutOptions& lo = {}) {
    const Layout l = make_layout(mask, lo);
    ExportSizeRecord r;
    r.mask = name;
    r.pinholes = l.polygons.size();
    // Named fields assigned on a default WriteOptions: a designated initializer that skips the
    // nested gds/dxf/pdf members draws gcc's -Wmissing-field-initializers.
    WriteOptions hierarchy;
    hierarchy.gds_hierarchy = true;
    const std::string flat = write_fabrication_bytes(l, FabFormat::kGds, {});
    const std::string cells = write_fabrication_bytes(l, FabFormat::kGds, hierarchy);
    const std::string oas = write_fabrication_bytes(l, FabFormat::kOasis, {});
    for (const auto& [bytes, f] :
         {std::pair{&flat, FabFormat::kGds}, {&cells, FabFormat::kGds}, {&oas, FabFormat::kOasis}})
        if (!read_back(*bytes, f, l).identical())
            throw RuntimeFailure("bench: " + fab_format_name(f) + " file of " + name +
                                 " does not read back as its layout");
    r.flat_gds_bytes = flat.size();
    r.cells_gds_bytes = cells.size();
    r.oasis_bytes = oas.size();
    return r;
}

}  // namespace

ExportBenchResult bench_export(const ExportBenchOptions& o) {
    if (o.n < 16 || o.n > kMaxGrid)
        throw invalid_field("n", std::to_string(o.n), "must be in 16.." + std::to_string(kMaxGrid));
    if (o.repeat < 1) throw invalid_field("repeat", std::to_string(o.repeat), "must be >= 1");
    if (o.scratch_dir.empty()) throw invalid_field("scratch_dir", "''", "must be given");
    fs::create_directories(o.scratch_dir);
    struct Cleanup {
        fs::path dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{o.scratch_dir};

    ExportBenchResult res;
    const Mask mask = bench_mask(o);
    res.pinholes = mask.pattern.pinholes.size();
    Layout layout;
    const Timing t_layout = time_min(o.repeat, [&] { layout = make_layout(mask, {}); });
    res.polygons = layout.polygons.size();
    std::vector<Ring> copy;
    const Timing t_copy = time_min(o.repeat, [&] { copy = layout.polygons; });
    res.records.push_back(record("layout", t_layout, 0, "copy the polygon list", t_copy));
    res.total_seconds = t_layout.wall;
    res.total_cpu_seconds = t_layout.cpu;

    for (FabFormat f : {FabFormat::kSvg, FabFormat::kPdf, FabFormat::kGds, FabFormat::kOasis,
                        FabFormat::kDxf, FabFormat::kGerber, FabFormat::kPng}) {
        const fs::path path = o.scratch_dir / ("bench" + fab_extension(f));
        const fs::path ref = o.scratch_dir / ("reference" + fab_extension(f));
        std::string bytes;
        WriteOptions wo;
        wo.png_dpi = o.dpi;
        const Timing t = time_min(o.repeat, [&] {
            bytes = write_fabrication_bytes(layout, f, wo);
            fwrite_file(path, bytes);
        });
        const Timing t_ref = time_min(o.repeat, [&] { fwrite_file(ref, bytes); });
        const std::string name = fab_format_name(f);
        res.records.push_back(
            record(name + " write", t, bytes.size(), "fwrite of the same bytes", t_ref));
        res.total_seconds += t.wall;
        res.total_cpu_seconds += t.cpu;
        if (!is_readable(f)) continue;
        std::size_t rings = 0;
        const Timing t_read =
            time_min(o.repeat, [&] { rings = read_fabrication_bytes(bytes, f).rings.size(); });
        if (rings != layout.polygons.size())
            throw RuntimeFailure("bench: " + name + " read back " + std::to_string(rings) +
                                 " rings, wrote " + std::to_string(layout.polygons.size()));
        std::string dup;
        const Timing t_dup = time_min(o.repeat, [&] { dup = bytes; });
        res.records.push_back(
            record(name + " read", t_read, bytes.size(), "copy the bytes", t_dup));
    }
    // Data volume: the bench mask as one tile, and the same cell count as a quarter-size
    // pattern tiled 4 x 4 (the cyclic tiling every coded mask has).
    res.sizes.push_back(sizes_of(std::to_string(o.n) + "^2 cells, 1 tile", mask));
    LayoutOptions apart;
    apart.hole_side_m = 0.5 * o.pinhole_m;  // neighbours apart
    res.sizes.push_back(sizes_of(std::to_string(o.n) + "^2 uniform random",
                                 uniform_mask(o, mask.pattern.pinholes.size()), apart));
    if (o.n % 4 == 0 && o.n >= 64)
        res.sizes.push_back(sizes_of(std::to_string(o.n / 4) + "^2 cells x 4 x 4 tiles",
                                     bench_mask(o, o.n / 4, 4)));
    return res;
}

}  // namespace pinmask
