// `pinmask bench export`: layout, writers and readers on a 1024 x 1024-cell mask with ~10^5
// pinholes, each beside a reference timed in the same run (fwrite of the same bytes, copying
// the polygons or the bytes), as a ratio.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/export_bench.hpp"
#include "cli/commands.hpp"
#include "core/units/units.hpp"

namespace pinmask::cli {
namespace {

struct Options {
    ExportBenchOptions bench;
    std::string pinhole = "20um";
    bool json = false;
};

void run(Options o) {
    o.bench.pinhole_m = parse_length_m(o.pinhole, "--pinhole");
    o.bench.scratch_dir = std::filesystem::temp_directory_path() /
                          ("pinmask-bench-export-" + std::to_string(::getpid()));
    if (!o.json)
        std::fprintf(stderr, "export bench: %d x %d cells, %d run(s) per figure...\n", o.bench.n,
                     o.bench.n, o.bench.repeat);
    const ExportBenchResult r = bench_export(o.bench);
    if (o.json) {
        nlohmann::json j = {{"pinholes", r.pinholes},
                            {"polygons", r.polygons},
                            {"total_seconds", r.total_seconds},
                            {"total_cpu_seconds", r.total_cpu_seconds},
                            {"records", nlohmann::json::array()}};
        for (const auto& rec : r.records)
            j["records"].push_back({{"stage", rec.stage},
                                    {"seconds", rec.seconds},
                                    {"cpu_seconds", rec.cpu_seconds},
                                    {"bytes", rec.bytes},
                                    {"reference", rec.reference},
                                    {"reference_seconds", rec.reference_seconds},
                                    {"reference_cpu_seconds", rec.reference_cpu_seconds},
                                    {"ratio", rec.ratio}});
        j["sizes"] = nlohmann::json::array();
        for (const auto& z : r.sizes)
            j["sizes"].push_back({{"mask", z.mask},
                                  {"pinholes", z.pinholes},
                                  {"flat_gds_bytes", z.flat_gds_bytes},
                                  {"cells_gds_bytes", z.cells_gds_bytes},
                                  {"oasis_bytes", z.oasis_bytes}});
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::printf("%zu pinholes -> %zu polygons; layout + all writes: %.3f s CPU (%.3f s wall)\n",
                r.pinholes, r.polygons, r.total_cpu_seconds, r.total_seconds);
    std::printf("%-13s %9s %9s %10s %9s %9s %8s  %s\n", "stage", "cpu s", "wall s", "bytes",
                "ref cpu s", "ref wall", "ratio", "reference");
    for (const auto& rec : r.records)
        std::printf("%-13s %9.4f %9.4f %10zu %9.4f %9.4f %8.1f  %s\n", rec.stage.c_str(),
                    rec.cpu_seconds, rec.seconds, rec.bytes, rec.reference_cpu_seconds,
                    rec.reference_seconds, rec.ratio, rec.reference.c_str());
    std::printf("\ndata volume (bytes; ratio = flat GDSII / this file):\n");
    for (const auto& z : r.sizes)
        std::printf(
            "  %-28s %7zu pinholes  flat GDSII %10zu  GDSII cells %10zu (%.1fx)  "
            "OASIS %10zu (%.1fx)\n",
            z.mask.c_str(), z.pinholes, z.flat_gds_bytes, z.cells_gds_bytes,
            double(z.flat_gds_bytes) / double(z.cells_gds_bytes), z.oasis_bytes,
            double(z.flat_gds_bytes) / double(z.oasis_bytes));
}

void setup(CLI::App& bench) {
    auto o = std::make_shared<Options>();
    auto* cmd = bench.add_subcommand(
        "export",
        "Export speed on an n x n-cell mask with ~n^2/10.5 pinholes (a seeded jittered "
        "lattice): layout, every writer (including the disk write) and every reader, each "
        "beside a reference timed in the same run (fwrite of the same bytes; copying the "
        "polygon list or the bytes), as a ratio of CPU times (wall times shown too). Minimum "
        "over --repeat runs.");
    cmd->add_option("--n", o->bench.n, "Cells per side (default 1024)");
    cmd->add_option("--pinhole", o->pinhole, "Cell pitch (length; default 20um)");
    cmd->add_option("--dpi", o->bench.dpi, "PNG preview resolution (default 2400)");
    cmd->add_option("--repeat", o->bench.repeat, "Runs per figure, minimum taken (default 3)");
    cmd->add_option("--seed", o->bench.seed, "Seed of the pinhole lattice (default 1)");
    cmd->add_flag("--json", o->json, "Print the figures as JSON on stdout");
    cmd->footer("Example:\n  pinmask bench export --repeat 1 --json");
    cmd->callback([o] { run(*o); });
}

}  // namespace

void add_bench_export(CLI::App& bench) { setup(bench); }
}  // namespace pinmask::cli
