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
#include "decode/depthmap/depthmap_capture.hpp"
#include "decode/depthmap/depthmap_planes.hpp"
#include "design/pattern/mask.hpp"

namespace pinmask {

struct DepthmapRequest {
    Image capture;               // read as grey: channels averaged
    std::string capture_name;    // its file, for the summary ("" when given as an array)
    std::string mask_name;       // the mask's file ("" none or not a file)
    std::string psf_stack_name;  // the stack's file ("" none or not a file)
    std::optional<Mask> mask;    // PSFs from its exact geometry, at steps distances from .. to
    // The sweep's range and count; nullopt: decode/depthmap/depthmap_planes's defaults (the
    // design's usable distances, planes one resolvable step apart). to_m may be inf.
    std::optional<double> from_m, to_m;
    std::optional<int> steps;
    std::vector<PsfStackPlane> psf_stack;  // instead of the mask
    // decode's capture steps where the sweep needs them (decode/depthmap/depthmap_capture).
    DepthmapCaptureOptions capture_options;
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
    std::optional<DepthmapPlaneChoice> planes;  // with a mask: the range, count and resolution
    std::string capture_name, mask_name, psf_stack_name;
    double wiener_nsr = 0.0;
    int window = 0;
    double smooth = 0.0;
    DepthmapCaptureOptions capture_options;
    double background = 0;           // counts subtracted from the capture
    std::vector<std::string> files;  // names of the files written (set when written)
};

DepthmapReport run_depthmap_request(DepthmapRequest request);

}  // namespace pinmask
