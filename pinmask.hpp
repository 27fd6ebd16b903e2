// The library's front door: one include for the main job, from a camera to a decoded scene.
//   camera and optics       design/optics/camera, design/optics/optics,
//   design/optics/working_distance pattern and mask        design/pattern/pattern,
//   design/pattern/families, design/pattern/generate_pattern, design/pattern/mask PSF
//   design/psf/kernel, design/psf/psf_settings, design/psf/psf simulation optimize/simulate/scenes,
//   optimize/simulate/noise_model, optimize/simulate/simulate,
//                           optimize/simulate/simulate_pipeline, optimize/simulate/image_quality
//                           (MSE, PSNR, SSIM)
//   metrics                 optimize/metrics/mask_metrics, optimize/metrics/analytic_error,
//   optimize/metrics/compare, ... search                  optimize/search/search_pipeline,
//   optimize/search/sweep decode                  decode/capture/decoder, decode/solvers/wiener,
//   decode/capture/capture_pipeline, decode/capture/batch calibration decode/calibrate/calibrate,
//   decode/calibrate/calibrated_psf depth from one capture  decode/depthmap/depthmap fabrication
//   export      export/pipeline/export_pipeline, export/pipeline/export_request,
//   export/pipeline/file_check files                   io/mask_json, io/camera_json, io/psf_files,
//   core/image/image_io
// Everything is in namespace pinmask (the file codecs in pinmask::io). The command (cli/) and the
// Python module (python/) are faces over these libraries and are not part of it. Installed as
// <prefix>/include/pinmask/pinmask.hpp beside the folders it includes, so with
// <prefix>/include/pinmask on the include path (the pinmask::pinmask CMake target sets it) both
// `#include "pinmask.hpp"` and `#include "core/fft/fft.hpp"` work.
#pragma once

// Errors, images and image files, FFT set-up.
#include "core/errors/error.hpp"
#include "core/fft/fft.hpp"
#include "core/fft/fft_environment.hpp"
#include "core/image/image.hpp"
#include "core/image/image_io.hpp"
#include "core/image/raw_io.hpp"
#include "core/limits/resource_limits.hpp"
#include "core/units/units.hpp"
#include "core/version.hpp"

// Camera, optics, patterns, masks and their PSF.
#include "design/optics/camera.hpp"
#include "design/optics/optics.hpp"
#include "design/optics/working_distance.hpp"
#include "design/pattern/families.hpp"
#include "design/pattern/generate_pattern.hpp"
#include "design/pattern/mask.hpp"
#include "design/pattern/mura.hpp"
#include "design/pattern/pattern.hpp"
#include "design/pattern/random_sparse.hpp"
#include "design/psf/kernel.hpp"
#include "design/psf/psf.hpp"
#include "design/psf/psf_exact.hpp"
#include "design/psf/psf_settings.hpp"

// Scenes, noise and the forward simulation of a capture; image quality.
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/noise_model.hpp"
#include "optimize/simulate/scene_prior.hpp"
#include "optimize/simulate/scenes.hpp"
#include "optimize/simulate/simulate.hpp"
#include "optimize/simulate/simulate_pipeline.hpp"

// Figures of merit of a mask.
#include "optimize/metrics/analytic_error.hpp"
#include "optimize/metrics/autocorrelation.hpp"
#include "optimize/metrics/compare.hpp"
#include "optimize/metrics/depth_loss.hpp"
#include "optimize/metrics/mask_metrics.hpp"
#include "optimize/metrics/metric_spellings.hpp"
#include "optimize/metrics/noise_levels.hpp"
#include "optimize/metrics/robust_errors.hpp"
#include "optimize/metrics/simulated_metrics.hpp"
#include "optimize/metrics/spectrum_metrics.hpp"

// Mask search and design sweeps.
#include "optimize/search/search.hpp"
#include "optimize/search/search_pipeline.hpp"
#include "optimize/search/sweep.hpp"

// Decoding captures.
#include "decode/capture/batch.hpp"
#include "decode/capture/capture.hpp"
#include "decode/capture/capture_pipeline.hpp"
#include "decode/capture/decode_request.hpp"
#include "decode/capture/decoder.hpp"
#include "decode/solvers/wiener.hpp"

// Calibration from a point-source capture.
#include "decode/calibrate/calibrate.hpp"
#include "decode/calibrate/calibrated_psf.hpp"

// Depth and an all-in-focus image from one capture.
#include "decode/depthmap/depthmap.hpp"

// Fabrication files: the export pipeline, its request, presets, design-rule and file checks.
#include "export/formats/read_any.hpp"
#include "export/formats/write_any.hpp"
#include "export/pipeline/drc.hpp"
#include "export/pipeline/export_pipeline.hpp"
#include "export/pipeline/export_request.hpp"
#include "export/pipeline/file_check.hpp"
#include "export/pipeline/vendor_presets.hpp"

// Mask, camera and PSF files.
#include "io/camera_json.hpp"
#include "io/mask_json.hpp"
#include "io/optics_json.hpp"
#include "io/psf_files.hpp"
