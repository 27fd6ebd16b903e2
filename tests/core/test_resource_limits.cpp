// The memory bound (core/limits/resource_limits) and the places that apply it: every large request
// of the commands (a 4096-grid PSF, random placement on a 4096 grid, a full-sensor simulation, a
// huge declared image, decoding a large capture, a layout of many pinholes) is refused with
// ResourceLimit, the figure in the message, under a small PINMASK_MEMORY_LIMIT.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/image/image_io.hpp"
#include "core/limits/resource_limits.hpp"
#include "decode/capture/decoder.hpp"
#include "design/pattern/mask.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/psf.hpp"
#include "export/layout/geometry.hpp"
#include "optimize/simulate/simulate.hpp"

using namespace pinmask;

namespace {

// Sets PINMASK_MEMORY_LIMIT for one scope and restores the previous value.
class MemoryLimit {
  public:
    explicit MemoryLimit(const char* value) {
        if (const char* old = std::getenv("PINMASK_MEMORY_LIMIT")) old_ = old;
        if (value) {
            ::setenv("PINMASK_MEMORY_LIMIT", value, 1);
        } else {
            ::unsetenv("PINMASK_MEMORY_LIMIT");
        }
    }
    ~MemoryLimit() {
        if (old_) {
            ::setenv("PINMASK_MEMORY_LIMIT", old_->c_str(), 1);
        } else {
            ::unsetenv("PINMASK_MEMORY_LIMIT");
        }
    }
    MemoryLimit(const MemoryLimit&) = delete;
    MemoryLimit& operator=(const MemoryLimit&) = delete;

  private:
    std::optional<std::string> old_;
};

constexpr std::size_t kMiB = std::size_t{1} << 20;

// MemTotal from /proc/meminfo in bytes: an independent reading of the machine's memory.
std::size_t mem_total_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::size_t kib = 0;
    std::string unit;
    while (in >> key >> kib >> unit) {
        if (key == "MemTotal:") return kib * 1024;
    }
    return 0;
}

Mask grid_mask(int n) {
    Mask m;
    m.pattern.n = n;
    m.pattern.tiles_rows = m.pattern.tiles_cols = 1;
    m.pattern.pinholes = {{0, 0}, {n / 2, n / 3}, {n - 3, 5}};
    m.camera = paper_camera();
    m.psf.pixels_per_cell = 8;
    m.psf.kernel.model = "box";
    return m;
}

}  // namespace

TEST_CASE("PINMASK_MEMORY_LIMIT: bytes or K/M/G suffix; default half the machine's memory") {
    {
        MemoryLimit limit("64M");
        CHECK(memory_limit_bytes() == 64 * kMiB);
    }
    {
        MemoryLimit limit("3G");
        CHECK(memory_limit_bytes() == 3 * 1024 * kMiB);
    }
    {
        MemoryLimit limit("512k");
        CHECK(memory_limit_bytes() == 512 * 1024);
    }
    {
        MemoryLimit limit("1048577");
        CHECK(memory_limit_bytes() == 1048577);
    }
    {
        MemoryLimit limit(nullptr);
        const std::size_t total = mem_total_bytes();
        REQUIRE(total > 0);
        CHECK(memory_limit_bytes() == total / 2);
    }
}

TEST_CASE("PINMASK_MEMORY_LIMIT: nonsense, zero, negative, overflowing values are refused") {
    // 1e400 is infinite and 1e30G beyond 2^64 bytes: converting them to size_t was undefined
    // behaviour (found while writing this test); now InvalidInput like the other bad values.
    for (const char* bad : {"abc", "0", "-5M", "8X", "1e400", "1e30G", "nan"}) {
        MemoryLimit limit(bad);
        INFO(bad);
        CHECK_THROWS_WITH_AS(memory_limit_bytes(), doctest::Contains("PINMASK_MEMORY_LIMIT"),
                             InvalidInput);
    }
}

TEST_CASE("PINMASK_TIME_LIMIT: durations with units or plain seconds, within 1 us .. 1e7 s") {
    // Independent references: the units' definitions written out.
    CHECK(parse_time_limit_s("90s") == 90.0);
    CHECK(parse_time_limit_s("90") == 90.0);
    CHECK(parse_time_limit_s("2m") == 120.0);
    CHECK(parse_time_limit_s("2min") == 120.0);
    CHECK(parse_time_limit_s("1.5h") == 5400.0);
    CHECK(parse_time_limit_s("500ms") == 0.5);
    CHECK(parse_time_limit_s("1e-6") == 1e-6);
    CHECK(parse_time_limit_s("1e7") == 1e7);
    for (const char* bad : {"", "0", "0s", "-1", "-5m", "nan", "inf", "1e400", "1e307h", "1e-9",
                            "1e8", "200000m", "2y", "2mm", "m", "soon", "5 parsecs"}) {
        INFO(bad);
        try {
            (void)parse_time_limit_s(bad);
            FAIL("accepted");
        } catch (const InvalidInput& e) {
            CHECK(std::string(e.what()).find("PINMASK_TIME_LIMIT") != std::string::npos);
        }
    }
}

TEST_CASE("the time budget applies inside a TimeLimitScope only, and then stops polls") {
    start_time_limit(1e-6);
    REQUIRE(time_limit_s() == 1e-6);
    {
        const TimeLimitScope scope;
        while (!time_limit_spent()) {
        }  // 1 us: spent at once on any machine; no figure asserted
        CHECK_THROWS_AS(check_time_limit("the test's loop"), TimeLimitSpent);
        try {
            check_time_limit("the test's loop");
        } catch (const TimeLimitSpent& e) {
            CHECK(std::string(e.what()) ==
                  "the time limit PINMASK_TIME_LIMIT = 1e-06 s was spent: the test's loop");
        }
        // Not an input error: the command line gives it its own exit code.
        CHECK_THROWS_AS(check_time_limit("x"), Error);
        TimeLimitPoll poll("the poll");
        for (int i = 0; i < 4095; ++i) poll();  // reads the clock at the 4096th call only
        CHECK_THROWS_AS(poll(), TimeLimitSpent);
    }
    // Without a scope (export, the Python module) a spent budget changes nothing.
    CHECK_FALSE(time_limit_spent());
    CHECK_NOTHROW(check_time_limit("outside"));
    start_time_limit(1e7);  // leave the process with a budget that no later test can spend
    const TimeLimitScope scope;
    CHECK_FALSE(time_limit_spent());
}

TEST_CASE("check_memory refuses above the bound with both figures, accepts up to it") {
    MemoryLimit limit("64M");
    CHECK_NOTHROW(check_memory(64.0 * kMiB, "exactly the bound"));
    CHECK_THROWS_WITH_AS(check_memory(64.0 * kMiB + 1, "a test request"),
                         doctest::Contains("a test request needs"), ResourceLimit);
    CHECK_THROWS_WITH_AS(check_memory(2.0 * 1024 * kMiB, "x"),
                         "x needs 2 GiB, more than the memory bound 0.0625 GiB (set "
                         "PINMASK_MEMORY_LIMIT to change it)",
                         ResourceLimit);
    // ResourceLimit is an InvalidInput: the CLI maps it to exit code 2.
    CHECK_THROWS_AS(check_memory(1e300, "x"), InvalidInput);
}

TEST_CASE("psf of a 4096 grid: refused with the PSF size and the figure before allocating") {
    MemoryLimit limit("64M");
    // 32768^2 doubles = 8 GiB for the PSF plane alone.
    CHECK_THROWS_WITH_AS(mask_psf(grid_mask(4096)), doctest::Contains("32768 x 32768 PSF"),
                         ResourceLimit);
    CHECK_THROWS_WITH_AS(check_psf_memory(4096, 8, 1, 0), doctest::Contains("needs 8 GiB"),
                         ResourceLimit);
    // The same call fits once the bound allows it (a small grid).
    CHECK_NOTHROW(check_psf_memory(16, 8, 4, 2));
}

TEST_CASE("generate on a 4096 grid: random placement refused under a 1 MiB bound") {
    MemoryLimit limit("1M");
    RandomSparseOptions o;
    o.n = 4096;
    o.holes = 1000;
    o.tiles_rows = o.tiles_cols = 1;
    std::mt19937_64 rng(1);
    CHECK_THROWS_WITH_AS(random_sparse_pattern(o, rng), doctest::Contains("4096 x 4096"),
                         ResourceLimit);
}

TEST_CASE("simulate: a 10^9-pixel sensor frame is refused") {
    MemoryLimit limit("64M");
    const Plane period = Plane::Constant(28, 28, 0.5);
    CHECK_THROWS_WITH_AS(tile_period(period, 31623, 31623, {0, 0}),
                         doctest::Contains("31623 x 31623"), ResourceLimit);
}

TEST_CASE("decode: a capture whose working set exceeds the bound is refused") {
    const Plane capture = Plane::Constant(1024, 1024, 0.5);  // 8 MiB
    Plane psf = Plane::Zero(1024, 1024);
    psf(512, 512) = 1.0;
    MemoryLimit limit("16M");
    DecodeOptions o;
    CHECK_THROWS_WITH_AS(decode_plane(capture, psf, o), doctest::Contains("memory bound"),
                         ResourceLimit);
}

TEST_CASE("read_image: declared sizes are checked against the bound before reading the data") {
    MemoryLimit limit("64M");
    // A valid 16 KB all-zero 4000^2 PNG: 128 MB as doubles, refused from its header.
    const auto path = std::filesystem::path(PINMASK_SOURCE_DIR) / "tests" / "bad-inputs" /
                      "capture-zeros-4000.png";
    CHECK_THROWS_WITH_AS(read_image(path), doctest::Contains("memory bound 0.0625 GiB"),
                         ResourceLimit);
    // The 249 KB all-zero 16000^2 PNG is refused from its header under any bound: beyond
    // kMaxImageSamples.
    MemoryLimit big("100G");
    CHECK_THROWS_WITH_AS(read_image(path.parent_path() / "capture-zeros-16000.png"),
                         doctest::Contains("kMaxImageSamples"), InvalidInput);
}

TEST_CASE("the budget is per process: reservations add up, and are given back") {
    MemoryLimit limit("100M");
    const double mib = 1024.0 * 1024.0;
    CHECK(memory_reserved_bytes() == 0);
    {
        MemoryReservation a(60 * mib, "first");
        CHECK_NOTHROW(check_memory(30 * mib, "fits beside"));
        // Each fits alone; together they exceed the bound: the second is refused, naming what
        // the run already holds.
        CHECK_THROWS_WITH_AS(MemoryReservation(60 * mib, "second"),
                             doctest::Contains("beside the 0.0586 GiB this run already holds"),
                             ResourceLimit);
        CHECK_THROWS_AS(check_memory(60 * mib, "third"), ResourceLimit);
        MemoryReservation moved = std::move(a);
        CHECK(memory_reserved_bytes() == std::size_t(60 * mib));
        moved.shrink_to(10 * mib);
        CHECK(memory_reserved_bytes() == std::size_t(10 * mib));
        // A large Image charges itself for as long as any copy lives.
        Image img(2000, 2000, 1);  // 30.5 MiB
        CHECK(memory_reserved_bytes() == std::size_t(10 * mib) + 8u * 2000 * 2000);
        Image copy = img;
        CHECK_THROWS_AS(Image(3000, 3000, 1), ResourceLimit);  // 68.7 MiB more: over
        img = Image();
        CHECK(memory_reserved_bytes() == std::size_t(10 * mib) + 8u * 2000 * 2000);
    }
    CHECK(memory_reserved_bytes() == 0);
    CHECK_THROWS_AS(check_memory(std::nan(""), "NaN bytes"), ResourceLimit);
    CHECK_THROWS_AS(MemoryReservation(-1.0, "negative"), ResourceLimit);
}

TEST_CASE("export: the layout of a huge pattern is refused under the bound") {
    MemoryLimit limit("1M");
    Mask m = grid_mask(4096);
    m.camera.pinhole_m = 10e-6;  // 4096 x 10 um = 41 mm: within the layout's coordinate range
    m.pattern.pinholes.clear();
    for (int r = 0; r < 4096; r += 2) {
        for (int c = 0; c < 64; c += 2) m.pattern.pinholes.push_back({r, c});
    }
    CHECK_THROWS_WITH_AS(make_layout(m, LayoutOptions{}), doctest::Contains("memory bound"),
                         ResourceLimit);
}

// FFTW cannot report a failed allocation (fftw_malloc failing aborts inside FFTW: "alloc.c:
// assertion failed"), so planning a transform is checked against the budget first: its scratch
// buffers (the input and the output of one transform) must fit beside what is reserved.
TEST_CASE("FFT plans: a plan whose scratch buffers exceed the bound is refused before planning") {
    MemoryLimit limit("64M");
    // Odd sizes no other test plans, so the plan cache cannot answer without planning.
    // 4099 x 4097 doubles: 134 MB in, 134 MB of half spectrum out.
    CHECK_THROWS_WITH_AS(Fft2(4099, 4097), doctest::Contains("planning an FFT of 4099 x 4097"),
                         ResourceLimit);
    CHECK_THROWS_WITH_AS(Fft2f(4099, 4097), doctest::Contains("more than the memory bound"),
                         ResourceLimit);
    CHECK_THROWS_WITH_AS(FftC2(2051, 2053), doctest::Contains("planning an FFT of 2051 x 2053"),
                         ResourceLimit);
    // 1001 x 1003 doubles: 8 MB + 8 MB, well inside; planned and usable.
    const Fft2 fits(1001, 1003);
    Plane x = Plane::Zero(1001, 1003);
    x(0, 0) = 1.0;
    const ComplexPlane spectrum = fits.forward(x);
    CHECK(std::abs(spectrum(500, 400) - std::complex<double>(1.0, 0.0)) < 1e-12);
}
