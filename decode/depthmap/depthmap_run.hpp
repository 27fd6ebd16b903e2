// The depthmap transaction: one capture, a mask (PSFs from its exact geometry at distances from
// .. to) or a PSF stack, to a depth map, its confidence, and an all-in-focus image. One call
// (run_depthmap_request) for both faces; io/depthmap_json renders the summary and writes the files.
// The faces read the capture, the mask and the stack.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.hpp"
#include "decode/depthmap/depthmap.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct DepthmapRequest {
    Image capture;                    // read as grey: channels averaged
    std::string capture_name;         // its file, for the summary ("" when given as an array)
    std::string mask_name;            // the mask's file ("" none or not a file)
    std::string psf_stack_name;       // the stack's file ("" none or not a file)
    std::optional<Mask> mask;         // PSFs from its exact geometry, at steps distances from .. to
    double from_m = 0.0, to_m = 0.0;  // to_m may be inf
    int steps = 16;
    std::vector<PsfStackPlane> psf_stack;  // instead of the mask
    double wiener_nsr = 0.01;
    int window = 121;
    double smooth = kDepthmapDefaultSmooth;
    const std::atomic<bool>* stop = nullptr;  // ends the sweep after the current plane
    // Called with done = 0 as the sweep starts, then after each plane.
    std::function<void(std::size_t done, std::size_t total)> progress;
};

struct DepthmapReport {
    DepthmapResult result;
    std::size_t planes_planned = 0;
    std::string capture_name, mask_name, psf_stack_name;
    double wiener_nsr = 0.0;
    int window = 0;
    double smooth = 0.0;
    std::vector<std::string> files;  // names of the files written (set when written)
};

DepthmapReport run_depthmap_request(DepthmapRequest request);

}  // namespace pinmask
