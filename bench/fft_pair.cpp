#include "bench/fft_pair.hpp"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <ctime>
#include <limits>
#include <string>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/fft/fftw_api.hpp"

namespace pinmask {

FftPairTime measured_fft_pair(int rows, int cols, int repeat, int threads) {
    if (rows < 1 || cols < 1 || repeat < 1 || threads < 1)
        throw InvalidInput("measured_fft_pair: rows, cols, repeat and threads must be >= 1");
    (void)fft_threads();  // core/fft/fft initialises FFTW's threads with its planner state
    using F = Fftw<double>;
    const std::size_t real = static_cast<std::size_t>(rows) * cols;
    const std::size_t half = static_cast<std::size_t>(rows) * (cols / 2 + 1);
    double* x = F::alloc_real(real);
    auto* spec = F::alloc_complex(half);
    F::plan_with_nthreads(threads);
    auto r2c = F::r2c(rows, cols, x, spec, FFTW_MEASURE);
    auto c2r = F::c2r(rows, cols, spec, x, FFTW_MEASURE);
    for (std::size_t i = 0; i < real; ++i) x[i] = static_cast<double>(i % 97) / 97.0;
    FftPairTime best{std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity()};
    for (int k = 0; k < repeat; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        F::execute(r2c);
        F::execute(c2r);
        best.wall_seconds =
            std::min(best.wall_seconds,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        best.cpu_seconds = std::min(best.cpu_seconds, double(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    F::destroy(r2c);
    F::destroy(c2r);
    F::free(spec);
    F::free(x);
    return best;
}

}  // namespace pinmask
