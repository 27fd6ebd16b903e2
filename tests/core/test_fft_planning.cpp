// core/fft/fft planning: single precision against double, FFTW_MEASURE plans remembered in a wisdom
// file (written, re-read, refused when corrupt or foreign), threads, planning statistics.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/fft/fft.hpp"
#include "tests/support/random_plane.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

// float32 round trip: FFTW's float error is about eps_f (1.2e-7) times log2(N) (~17 at 480 x
// 720) in the l2 norm; 2e-6 leaves a factor ~1 of margin over 17 * 1.2e-7.
constexpr double kFloatRoundTripTol = 2e-6;

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Restores the library defaults (ESTIMATE, no wisdom, 1 thread) when a test ends.
struct PlannerGuard {
    ~PlannerGuard() {
        set_fft_wisdom_file("");
        set_fft_planner(FftPlanner::kEstimate);
        set_fft_threads(1);
    }
};

fs::path temp_file(const std::string& name) {
    return fs::temp_directory_path() / ("pinmask-fft-" + std::to_string(::getpid()) + "-" + name);
}

}  // namespace

TEST_CASE("Fft2f agrees with Fft2 to float rounding (forward spectrum and round trip)") {
    for (auto [R, C] : {std::pair{48, 64}, std::pair{37, 50}}) {
        const Plane x = test::random_plane(R, C, 7, -1.0, 1.0);
        const ComplexPlane ref = Fft2(R, C).forward(x);
        const Fft2f f(R, C);
        ComplexPlaneF spec;
        f.forward(x.cast<float>(), spec);
        const double err = (spec.cast<std::complex<double>>() - ref).abs2().sum();
        CHECK(std::sqrt(err / ref.abs2().sum()) <= kFloatRoundTripTol);
        PlaneF back;
        ComplexPlaneF scratch;
        f.inverse(spec, back, scratch);
        const double rt = std::sqrt((back.cast<double>() - x).square().sum() / x.square().sum());
        CHECK(rt <= kFloatRoundTripTol);
    }
}

TEST_CASE("wisdom: measured plans are written, trusted on re-read, and refused when damaged") {
    PlannerGuard guard;
    const fs::path path = temp_file("wisdom");
    fs::remove(path);
    set_fft_planner(FftPlanner::kMeasure);
    CHECK(set_fft_wisdom_file(path.string()).empty());  // absent: no warning
    const FftPlanStats before = fft_plan_stats();
    const Fft2 f(40, 36);  // a size no other test plans with FFTW_MEASURE
    const FftPlanStats after = fft_plan_stats();
    CHECK(after.plans == before.plans + 2);
    CHECK(after.planning_seconds >= before.planning_seconds);
    REQUIRE(fs::exists(path));
    const std::string text = slurp(path);
    CHECK(text.rfind("pinmask-fftw-wisdom 2\n", 0) == 0);
    CHECK(fft_wisdom_problem(text).empty());
    CHECK(set_fft_wisdom_file(path.string()).empty());  // re-read: trusted

    // Another CPU or FFTW version: refused, with the reason.
    std::string foreign = text;
    foreign.replace(foreign.find("\ncpu ") + 5, 3, "XYZ");
    CHECK(fft_wisdom_problem(foreign).find("another FFTW version or CPU") != std::string::npos);
    { std::ofstream(path, std::ios::binary) << foreign; }
    auto w = set_fft_wisdom_file(path.string());
    REQUIRE(w.size() == 1);
    CHECK(w[0].find("ignored") != std::string::npos);

    // Not ours / corrupt FFTW text: refused.
    { std::ofstream(path, std::ios::binary) << "(fftw-3.3.10 fftw_wisdom #x1 garbage"; }
    CHECK(set_fft_wisdom_file(path.string()).size() == 1);
    const std::string header = text.substr(0, text.find("[double]\n"));
    { std::ofstream(path, std::ios::binary) << header << "[double]\n(fftw-3.3 ((((\n[float]\n"; }
    w = set_fft_wisdom_file(path.string());
    REQUIRE(w.size() == 1);
    CHECK(w[0].find("corrupt") != std::string::npos);

    // A file of wisdom format 1 (other section marks): ignored like a stale file, then replaced
    // by the current format when plans are saved.
    std::string format1 = text;
    format1.replace(format1.find("wisdom 2\n"), 9, "wisdom 1\n");
    format1.replace(format1.find("[double]\n"), 9, "--- double\n");
    format1.replace(format1.find("[float]\n"), 8, "--- float\n");
    CHECK(fft_wisdom_problem(format1).find("another pinmask wisdom format") != std::string::npos);
    { std::ofstream(path, std::ios::binary) << format1; }
    w = set_fft_wisdom_file(path.string());
    REQUIRE(w.size() == 1);
    CHECK(w[0].find("ignored") != std::string::npos);
    CHECK(w[0].find("replaced") != std::string::npos);
    const Fft2 g(44, 30);  // a new measured plan: the wisdom is written again
    CHECK(slurp(path).rfind("pinmask-fftw-wisdom 2\n", 0) == 0);
    fs::remove(path);
}

TEST_CASE("threads: a threaded 512 x 512 transform gives the same bytes as a serial one") {
    PlannerGuard guard;
    const Plane x = test::random_plane(512, 512, 11, -1.0, 1.0);
    set_fft_threads(1);
    CHECK(fft_threads_for(512, 512) == 1);
    const Fft2 serial(512, 512);
    const ComplexPlane a = serial.forward(x);
    const Plane ia = serial.inverse(a);
    set_fft_threads(2);
    CHECK(fft_threads_for(512, 512) == 2);
    CHECK(fft_threads_for(256, 256) == 1);
    const Fft2 threaded(512, 512);
    const ComplexPlane b = threaded.forward(x);
    const Plane ib = threaded.inverse(b);
    CHECK((a == b).all());
    CHECK((ia == ib).all());
}
