// The library's front door: one include for the main job, from a camera to a decoded scene.
//   camera and optics       design/camera, design/optics, design/working_distance
//   pattern and mask        design/pattern, design/families, design/generate_pattern, design/mask
//   PSF                     design/kernel, design/psf_settings, design/psf
//   simulation              simulate/scenes, simulate/noise_model, simulate/simulate,
//                           simulate/simulate_pipeline, simulate/image_quality (MSE, PSNR, SSIM)
//   metrics                 metrics/mask_metrics, metrics/analytic_error, metrics/compare, ...
//   search                  search/search_pipeline, search/sweep
//   decode                  decode/decoder, decode/wiener, decode/capture_pipeline, decode/batch
//   calibration             calibrate/calibrate, calibrate/calibrated_psf
//   fabrication export      export/export_pipeline, export/export_request, export/file_check
//   files                   io/mask_json, io/camera_json, io/psf_files, core/image_io
// Everything is in namespace pinmask (the file codecs in pinmask::io). The command (cli/) and the
// Python module (python/) are faces over these libraries and are not part of it. Installed as
// <prefix>/include/pinmask/pinmask.hpp beside the folders it includes, so with
// <prefix>/include/pinmask on the include path (the pinmask::pinmask CMake target sets it) both
// `#include "pinmask.hpp"` and `#include "core/fft.hpp"` work.
#pragma once

// Errors, images and image files, FFT set-up.
#include "core/error.hpp"
#include "core/fft.hpp"
#include "core/fft_environment.hpp"
#include "core/image.hpp"
#include "core/image_io.hpp"
#include "core/raw_io.hpp"
#include "core/resource_limits.hpp"
#include "core/units.hpp"

// Camera, optics, patterns, masks and their PSF.
#include "design/camera.hpp"
#include "design/families.hpp"
#include "design/generate_pattern.hpp"
#include "design/kernel.hpp"
#include "design/mask.hpp"
#include "design/mura.hpp"
#include "design/optics.hpp"
#include "design/pattern.hpp"
#include "design/psf.hpp"
#include "design/psf_exact.hpp"
#include "design/psf_settings.hpp"
#include "design/random_sparse.hpp"
#include "design/working_distance.hpp"

// Scenes, noise and the forward simulation of a capture; image quality.
#include "simulate/image_quality.hpp"
#include "simulate/noise_model.hpp"
#include "simulate/scene_prior.hpp"
#include "simulate/scenes.hpp"
#include "simulate/simulate.hpp"
#include "simulate/simulate_pipeline.hpp"

// Figures of merit of a mask.
#include "metrics/analytic_error.hpp"
#include "metrics/autocorrelation.hpp"
#include "metrics/compare.hpp"
#include "metrics/depth_loss.hpp"
#include "metrics/mask_metrics.hpp"
#include "metrics/metric_spellings.hpp"
#include "metrics/noise_levels.hpp"
#include "metrics/robust_errors.hpp"
#include "metrics/simulated_metrics.hpp"
#include "metrics/spectrum_metrics.hpp"

// Mask search and design sweeps.
#include "search/search.hpp"
#include "search/search_pipeline.hpp"
#include "search/sweep.hpp"

// Decoding captures.
#include "decode/batch.hpp"
#include "decode/capture.hpp"
#include "decode/capture_pipeline.hpp"
#include "decode/decode_request.hpp"
#include "decode/decoder.hpp"
#include "decode/wiener.hpp"

// Calibration from a point-source capture.
#include "calibrate/calibrate.hpp"
#include "calibrate/calibrated_psf.hpp"

// Fabrication files: the export pipeline, its request, presets, design-rule and file checks.
#include "export/drc.hpp"
#include "export/export_pipeline.hpp"
#include "export/export_request.hpp"
#include "export/file_check.hpp"
#include "export/vendor_presets.hpp"
#include "formats/read_any.hpp"
#include "formats/write_any.hpp"

// Mask, camera and PSF files.
#include "io/camera_json.hpp"
#include "io/mask_json.hpp"
#include "io/optics_json.hpp"
#include "io/psf_files.hpp"
