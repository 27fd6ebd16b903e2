// A mask: the pattern, the camera it is designed for, how its PSF is synthesised, and where it
// came from. This is the in-memory form of `*.mask.json` (docs/design.md section 5); the JSON codec
// lives in io/mask_json (libraries do not parse JSON).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/pattern/pattern.hpp"

namespace pinmask {

// How the single-pinhole kernel is modelled. `model` is one of: auto, box, fraunhofer, fresnel,
// paper-fig3b, measured. `measured_path` names the kernel image for `measured`.
// `wavelengths` is a weighted list (wavelength_m, weight) for polychromatic kernels; empty means
// the camera's band (Camera::bandwidth_m, design/optics/spectrum; one wavelength when that is 0).
struct KernelSpec {
    std::string model = "auto";
    std::string measured_path;
    std::vector<std::pair<double, double>> wavelengths;
};

struct PsfSpec {
    KernelSpec kernel;
    int pixels_per_cell = 8;  // image-plane cell pitch in pixels (integer for exact sampling)
};

struct Provenance {
    std::uint64_t seed = 0;
    std::string generator;  // e.g. "pinmask generate 0.1.0"
    std::string family;     // random | paper | mura | ura | search:<strategy> | file
    bool spacing_violations_allowed = false;
    std::map<std::string, double> scores;  // metric name -> value, names carry units
    // The scores key of the figure a search optimised ("analytic_mmse_psnr_db", ...; "" for a
    // mask no search made): compare leads with it (optimize/metrics/compare.hpp).
    std::string objective_figure;
};

struct Mask {
    Pattern pattern;
    Camera camera;
    PsfSpec psf;
    Provenance provenance;
};

// Hex digest (16 hex digits, FNV-1a 64) of the mask's geometry: n, sorted pinholes, tiles,
// pinhole side in nanometres (rounded) and min spacing. Identical geometry -> identical hash,
// independent of pinhole order, camera distances, kernel and provenance.
std::string geometry_hash(const Mask& mask);

}  // namespace pinmask
