// Export speed: a 1024 x 1024-cell mask with about 10^5 square pinholes (a seeded jittered
// lattice: one pinhole in each 3 x 3 block, at a random corner of its 2 x 2 top-left sub-block,
// kept with probability 0.86, so the spacing rule 2.0 holds) is turned into a layout and written
// to every format, each file written to disk and the readable ones read back. Every stage is
// timed beside a reference measured in the same run, as a ratio:
//   layout            make_layout             vs copying the resulting polygon list
//   <format> write    writer + fwrite to disk vs fwrite of the same number of bytes
//   <format> read     reader on the bytes     vs copying the bytes
// and the data volume of flat GDSII, hierarchical GDSII (SREF/AREF and window cells) and OASIS
// for the mask as one tile, for as many uniformly random pinholes (no structure to share), and
// as an (n/4)^2 pattern tiled 4 x 4 (each file read back equal to its layout).
// Each stage is timed as wall-clock seconds and as CPU seconds of the calling thread (what "on
// one core" costs, undisturbed by other processes on a shared machine); each figure is the
// minimum over `repeat` runs. Ratios use the CPU times.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pinmask {

struct ExportBenchOptions {
    int n = 1024;              // cells per side, >= 16
    double pinhole_m = 20e-6;  // cell pitch (20 um: a 20.48 mm mask)
    double dpi = 2400;         // PNG preview resolution
    int repeat = 3;            // >= 1
    std::uint64_t seed = 1;
    std::filesystem::path scratch_dir;  // where files are written (created, then removed)
};

struct ExportBenchRecord {
    std::string stage;         // "layout", "svg write", "gds read", ...
    double seconds = 0.0;      // wall clock
    double cpu_seconds = 0.0;  // this thread's CPU time
    std::size_t bytes = 0;
    std::string reference;  // what the reference did
    double reference_seconds = 0.0;
    double reference_cpu_seconds = 0.0;
    double ratio = 0.0;  // cpu_seconds / reference_cpu_seconds
};

// Data volume of one mask in the formats mask shops price by (bytes).
struct ExportSizeRecord {
    std::string mask;  // what the mask is
    std::size_t pinholes = 0;
    std::size_t flat_gds_bytes = 0, cells_gds_bytes = 0, oasis_bytes = 0;
};

struct ExportBenchResult {
    std::size_t pinholes = 0;
    std::size_t polygons = 0;
    double total_seconds = 0.0;      // layout + every write, wall clock
    double total_cpu_seconds = 0.0;  // layout + every write, CPU time of the thread
    std::vector<ExportBenchRecord> records;
    std::vector<ExportSizeRecord> sizes;  // flat GDSII vs hierarchical GDSII vs OASIS
};

// Runs on the calling thread. Throws InvalidInput for options out of range (naming the field)
// and RuntimeFailure when the scratch directory cannot be written.
ExportBenchResult bench_export(const ExportBenchOptions& options);

}  // namespace pinmask
