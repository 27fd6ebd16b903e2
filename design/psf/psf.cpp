#include "design/psf/psf.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/limits/resource_limits.hpp"

namespace pinmask {
namespace {

int torus_side(int n, int ppc) { return n * ppc; }  // <= 4096 * 65536 < 2^31

void require_holes(const Pattern& p) {
    validate(p, /*allow_spacing_violations=*/true);
    if (p.pinholes.empty()) {
        throw invalid_field("pattern pinholes", "0", "the PSF needs at least one pinhole");
    }
}

// Adds `weight * kernel` with its origin at pixel (row0, col0) of the N x N torus.
void add_wrapped(Plane& torus, const Kernel& k, long long row0, long long col0, double weight) {
    const long long n = torus.rows();
    std::vector<Eigen::Index> cols(static_cast<std::size_t>(k.values.cols()));
    for (Eigen::Index j = 0; j < k.values.cols(); ++j) cols[j] = ((col0 + j) % n + n) % n;
    for (Eigen::Index i = 0; i < k.values.rows(); ++i) {
        const Eigen::Index r = ((row0 + i) % n + n) % n;
        for (Eigen::Index j = 0; j < k.values.cols(); ++j) {
            torus(r, cols[j]) += weight * k.values(i, j);
        }
    }
}

}  // namespace

void check_psf_memory(int n, int ppc, int planes_real, int planes_half) {
    if (n < 1 || n > kMaxGrid) {
        throw invalid_field("grid n", std::to_string(n),
                            "must be between 1 and " + std::to_string(kMaxGrid));
    }
    if (ppc < 1 || ppc > kMaxPixelsPerCell) {
        throw invalid_field("pixels_per_cell", std::to_string(ppc),
                            "must be between 1 and " + std::to_string(kMaxPixelsPerCell));
    }
    const double side = static_cast<double>(n) * ppc;
    const double bytes =
        planes_real * side * side * 8.0 + planes_half * side * (side / 2 + 1) * 16.0;
    const std::string size = std::to_string(static_cast<long long>(side));
    check_memory(bytes, "the " + size + " x " + size + " PSF (grid " + std::to_string(n) + " x " +
                            std::to_string(ppc) + " pixels per cell)");
}

Plane kernel_on_torus(const Kernel& k, int n, int ppc) {
    check_psf_memory(n, ppc, 1, 0);
    const int side = torus_side(n, ppc);
    Plane torus = Plane::Zero(side, side);
    add_wrapped(torus, k, k.origin_row, k.origin_col, 1.0);
    return torus;
}

Plane synthesize_psf(const Pattern& p, const Kernel& k, int ppc, PsfMethod method) {
    require_holes(p);
    check_psf_memory(p.n, ppc, 1, 0);
    const int side = torus_side(p.n, ppc);
    if (method == PsfMethod::kAuto) {
        const double direct = static_cast<double>(p.pinholes.size()) * k.values.size();
        const double area = static_cast<double>(side) * side;
        const double fourier = 3.0 * area * std::max(1.0, std::log2(area));  // two FFTs + product
        method = direct > 4.0 * fourier ? PsfMethod::kFourier : PsfMethod::kDirect;
    }
    if (method == PsfMethod::kFourier) {
        check_psf_memory(p.n, ppc, 2, 2);
        Plane a = Fft2(side, side).inverse(psf_otf(p, k, ppc));
        a = a.max(0.0);
        return a;
    }
    Plane torus = Plane::Zero(side, side);
    const double weight = 1.0 / static_cast<double>(p.pinholes.size());
    for (const Cell& c : p.pinholes) {
        add_wrapped(torus, k, static_cast<long long>(c.row) * ppc + k.origin_row,
                    static_cast<long long>(c.col) * ppc + k.origin_col, weight);
    }
    return torus;
}

ComplexPlane pattern_spectrum(const Pattern& p) {
    validate(p, /*allow_spacing_violations=*/true);
    Plane occ = Plane::Zero(p.n, p.n);
    for (const Cell& c : p.pinholes) occ(c.row, c.col) = 1.0;
    return expand_half_spectrum(Fft2(p.n, p.n).forward(occ), p.n);
}

ComplexPlane kernel_spectrum(const Kernel& k, int n, int ppc) {
    check_psf_memory(n, ppc, 1, 1);
    const int side = torus_side(n, ppc);
    return Fft2(side, side).forward(kernel_on_torus(k, n, ppc));
}

ComplexPlane combine_spectra(const ComplexPlane& pattern_full, const ComplexPlane& kernel_half,
                             int holes) {
    const Eigen::Index n = pattern_full.rows(), side = kernel_half.rows();
    if (n < 1 || pattern_full.cols() != n || side % n != 0 || kernel_half.cols() != side / 2 + 1 ||
        holes < 1) {
        throw InvalidInput(
            "combine_spectra: need an n x n pattern spectrum, an N x (N/2 + 1) "
            "kernel spectrum with N a multiple of n, and holes >= 1 (got " +
            std::to_string(n) + " x " + std::to_string(pattern_full.cols()) + ", " +
            std::to_string(side) + " x " + std::to_string(kernel_half.cols()) + ", " +
            std::to_string(holes) + ")");
    }
    ComplexPlane out(side, kernel_half.cols());
    const double inv_k = 1.0 / holes;
    for (Eigen::Index r = 0; r < side; ++r) {
        const Eigen::Index pr = r % n;
        for (Eigen::Index c = 0; c < kernel_half.cols(); ++c) {
            out(r, c) = pattern_full(pr, c % n) * kernel_half(r, c) * inv_k;
        }
    }
    return out;
}

ComplexPlane psf_otf(const Pattern& p, const Kernel& k, int ppc) {
    require_holes(p);
    check_psf_memory(p.n, ppc, 1, 2);
    return combine_spectra(pattern_spectrum(p), kernel_spectrum(k, p.n, ppc),
                           static_cast<int>(p.pinholes.size()));
}

Kernel mask_kernel(const Mask& mask, KernelOptions options) {
    const int ppc = mask.psf.pixels_per_cell;
    check_psf_memory(mask.pattern.n, ppc, 0, 0);
    const int side = torus_side(mask.pattern.n, ppc);
    options.max_width_px = std::min(options.max_width_px, side);
    Kernel k = make_kernel(mask.camera, mask.psf.kernel, ppc, options);
    if (k.values.rows() > side || k.values.cols() > side) {  // a table or image: not cut to fit
        throw invalid_field(
            "kernel",
            std::to_string(k.values.rows()) + " x " + std::to_string(k.values.cols()) + " px",
            "exceeds the period of " + std::to_string(side) + " x " + std::to_string(side) +
                " px (grid " + std::to_string(mask.pattern.n) + " x " + std::to_string(ppc) +
                " px per cell): it would fold onto itself; use a smaller kernel "
                "image or a larger grid");
    }
    return k;
}

Plane mask_psf(const Mask& mask, const KernelOptions& options) {
    require_holes(mask.pattern);
    check_psf_memory(mask.pattern.n, mask.psf.pixels_per_cell, 1, 0);
    return synthesize_psf(mask.pattern, mask_kernel(mask, options), mask.psf.pixels_per_cell);
}

}  // namespace pinmask
