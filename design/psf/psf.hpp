// The PSF of a mask on the torus (docs/design.md section 2). Notation: n grid, K pinholes, ppc pixels
// per cell (the mask's PsfSpec::pixels_per_cell), N = n * ppc the torus side in pixels.
//   A = (1/K) sum over pinholes (r, c) of the kernel placed at cell (r, c), i.e. shifted by
//       (r ppc, c ppc) pixels with wrap-around on the N x N torus; sum A = 1.
// Kernel placement is the convention of design/psf/kernel.hpp (continuous centre at the cell
// centre). Fourier form (core/fft/fft.hpp conventions, forward unnormalised): with P^ the n x n DFT
// of the 0/1 pattern and K0^ the N x N DFT of the kernel placed at cell (0, 0),
//   A^(k) = P^(k mod n) K0^(k) / K,
// because a shift by (r ppc, c ppc) multiplies frequency k by exp(-2 pi i (k . (r, c)) / n).
// Every function checks the memory it will need (core/limits/resource_limits) before allocating.
#pragma once

#include "core/image/image.hpp"
#include "design/pattern/mask.hpp"
#include "design/pattern/pattern.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask {

// Throws ResourceLimit when `planes_real` real N x N planes plus `planes_half` complex
// N x (N/2 + 1) half spectra would exceed the memory bound; InvalidInput for n or ppc out of
// range (1..kMaxGrid, 1..kMaxPixelsPerCell).
void check_psf_memory(int n, int pixels_per_cell, int planes_real, int planes_half);

// The kernel placed at cell (0, 0) of the N x N torus, folded by wrap-around (sum preserved).
Plane kernel_on_torus(const Kernel& kernel, int n, int pixels_per_cell);

// How synthesize_psf sums: kDirect adds the kernel at every pinhole (K x kernel-size work);
// kFourier inverts psf_otf (N^2 log N work, values below 0 from rounding, ~1e-17, set to 0);
// kAuto takes kFourier when the direct sum would cost more than 4 times as much.
enum class PsfMethod { kAuto, kDirect, kFourier };

// The PSF A (N x N, sum 1). The pattern must be structurally valid (spacing is not checked) and
// have at least one pinhole (InvalidInput otherwise).
Plane synthesize_psf(const Pattern& pattern, const Kernel& kernel, int pixels_per_cell,
                     PsfMethod method = PsfMethod::kAuto);

// P^: the full n x n DFT of the 0/1 pattern (not divided by K).
ComplexPlane pattern_spectrum(const Pattern& pattern);

// K0^: the half spectrum N x (N/2 + 1) of kernel_on_torus.
ComplexPlane kernel_spectrum(const Kernel& kernel, int n, int pixels_per_cell);

// A^ = P^(k mod n) K0^(k) / holes as a half spectrum, from the two spectra above. For incremental
// pattern updates: P^ changes by two plane waves per moved pinhole, K0^ stays.
ComplexPlane combine_spectra(const ComplexPlane& pattern_full, const ComplexPlane& kernel_half,
                             int holes);

// The half spectrum of synthesize_psf(pattern, kernel, ppc), by the factorisation.
ComplexPlane psf_otf(const Pattern& pattern, const Kernel& kernel, int pixels_per_cell);

// The mask's kernel: make_kernel(camera, psf.kernel, psf.pixels_per_cell, options) with the support
// capped at the torus side N (a wider support would only fold onto itself). A kernel that cannot
// be capped (a measured image, the paper's table) and is wider than N: InvalidInput naming both.
Kernel mask_kernel(const Mask& mask, KernelOptions options = {});

// synthesize_psf with mask_kernel.
Plane mask_psf(const Mask& mask, const KernelOptions& options = {});

}  // namespace pinmask
