// The design transaction: the optics report of a camera and pattern geometry at its working
// distance, with the pinhole solved for whole pixels per cell when asked (then snapped to the
// fabrication grid), the kernel psf would build and its validity, and the spacing rule's
// packing bound. One call (run_design_request) for both faces; each face parses and checks its
// settings (the grid from a length or an export preset); io/design_json renders the report as
// `design --json` prints it and Python's optics() returns it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "design/optics/camera.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/packing_bound.hpp"
#include "design/psf/design_kernel.hpp"
#include "design/psf/kernel_model.hpp"

namespace pinmask {

// A pinhole solved for N whole pixels per cell at u and snapped to the fabrication grid
// (design/optics/fab_grid): the exact solution, the side on the grid and how far the grid moves
// the pitch at u (px per cell; n times that across one period).
struct GridSnap {
    bool solved = false;
    std::int64_t grid_nm = 1;
    std::string grid_source;  // where the grid came from, in the face's words
    double exact_m = 0, on_grid_m = 0, pitch_shift_px = 0;
};

struct DesignRequest {
    Camera camera;  // its pinhole is the start of a solve
    PatternGeometry geometry;
    double spacing_cells = 2.0;
    KernelModel model = KernelModel::kAuto;  // the model reported
    std::string kernel = "auto";             // the same as psf's spelling (design_kernel)
    double lsi_tolerance_px = 1.0;
    std::optional<int> pixels_per_cell;  // solve d for N whole pixels per cell at u
    bool solve = false;                  // solve d for the whole N nearest the pitch at u
    // The grid a solved pinhole lands on, as given: a length (fab_grid_m; its text for
    // messages) or an export preset (vendor, and its grid: nullopt for a rule preset without
    // one). Neither: 1 nm. Given without a solve, or both, is refused.
    std::optional<double> fab_grid_m;
    std::string fab_grid_text;
    std::optional<std::string> vendor;
    std::optional<double> vendor_grid_m;
    // Where the face took each camera value from, in its words: (symbol, source) in the order
    // of kCameraInputSymbols ("flag", "camera file", "paper preset default", ...).
    std::vector<std::pair<std::string, std::string>> input_sources;
    // The face's spelling of the field references in the warnings (identity when not given).
    std::function<std::string(const std::string&)> spell;

    // The fabrication grid from fab_grid_m or the vendor's (InvalidInput naming the field when
    // both are given, when either is given without a solve, for a vendor without a grid, or a
    // grid that is not a whole number of nm); where it came from in the face's words.
    GridSnap grid() const;
};

// The camera values a design report names the source of, in the report's order (the pinhole
// first).
inline constexpr const char* kCameraInputSymbols[] = {
    "d (pinhole)",     "lambda (wavelength)", "B (bandwidth, FWHM)", "f (lens to sensor)",
    "f' (lens focal)", "u (object distance)", "w (pixel pitch)",     "sensor"};

struct DesignReport {
    Camera camera;  // as reported: a solved pinhole on the grid
    OpticsReport optics;
    WorkingDistance working;
    DesignKernel kernel;  // its validity warnings spelled by the face
    GridSnap snap;
    PackingUpperBound packing;  // on the pinhole count at the spacing rule
    // A solve for the nearest N that starts far from the optimum pinhole says where it is.
    std::string far_from_optimum;
    double spacing_cells = 2.0;  // the spacing rule the packing bound is for
    // The request's input sources; a solved pinhole's source says it was solved and snapped.
    std::vector<std::pair<std::string, std::string>> input_sources;
};

DesignReport run_design_request(const DesignRequest& request);

}  // namespace pinmask
