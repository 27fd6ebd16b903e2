// The main job of pinmask through its installed libraries, with one include: the paper's camera,
// a mask for it (the paper family: 16 x 16 cells, 20 pinholes, 2 x 2 tiles), its PSF, a simulated
// capture of the letter-R scene with Gaussian noise at 30 dB SNR, the Wiener decode, and the
// PSNR of the estimate against the scene. Prints the figures; exits 1 with the library's message
// on an error.
#include <cmath>
#include <cstdio>
#include <exception>

#include "pinmask.hpp"

namespace {

double mean_square(const pinmask::Plane& p) { return p.square().mean(); }

int run() {
    using namespace pinmask;

    // The camera and its optics report for the pattern geometry.
    Mask mask;
    mask.camera = paper_camera();
    GeneratePatternOptions generate;
    generate.family = Family::kPaper;
    generate.seed = 1;
    mask.pattern = generate_pattern(generate).pattern;
    const OpticsReport optics = compute_optics(mask.camera, geometry_of(mask.pattern));
    std::printf("camera: u %.1f m, f' %.0f mm, f %.0f mm, pinhole %.0f um, %.2f px per cell at u\n",
                mask.camera.object_distance_m, mask.camera.lens_focal_m * 1e3,
                mask.camera.sensor_distance_m * 1e3, mask.camera.pinhole_m * 1e6,
                optics.pixels_per_cell_at_u);
    std::printf("mask: %d x %d cells, %zu pinholes, tiles %d x %d, Fresnel number %.2f\n",
                mask.pattern.n, mask.pattern.n, mask.pattern.pinholes.size(),
                mask.pattern.tiles_rows, mask.pattern.tiles_cols, optics.fresnel_number_with_lens);

    // The PSF of one period: the kernel model and pixels per cell the camera resolves to
    // (kernel "auto": box, Fraunhofer or Fresnel by the Fresnel number).
    mask.psf = resolve_psf_spec(PsfSettings{}, mask.camera);
    const Kernel kernel = mask_kernel(mask);
    const Plane psf = synthesize_psf(mask.pattern, kernel, mask.psf.pixels_per_cell);
    std::printf("psf: %td x %td px (%d px per cell), kernel %s\n", psf.rows(), psf.cols(),
                mask.psf.pixels_per_cell, kernel_model_name(kernel.model).c_str());

    // A capture of the scene through the mask, one period, Gaussian noise at 30 dB SNR.
    const Image scene = make_scene(scene_from_name("letter-R"), static_cast<int>(psf.rows()),
                                   static_cast<int>(psf.cols()));
    SimulationOptions simulation;
    simulation.noise.kind = NoiseKind::kGaussianSnr;
    simulation.noise.snr_db = 30.0;
    simulation.seed = 1;
    const int holes = static_cast<int>(mask.pattern.pinholes.size());
    const SimulatedCapture capture =
        simulate_capture(scene, psf, holes, mask.pattern.n * mask.pattern.n, simulation);

    // Wiener with the noise-to-signal power ratio of this capture: the noise variance the SNR
    // sets over the scene's mean square.
    const double sigma = sigma_for_snr(mean_square(capture.clean.channels[0]), 30.0);
    DecodeOptions decode;
    decode.method = DecodeMethod::kWiener;
    decode.wiener.nsr = sigma * sigma / mean_square(scene.channels[0]);
    const DecodeResult estimate = decode_plane(capture.capture.channels[0], psf, decode);

    const double capture_psnr = psnr_db(capture.capture.channels[0], scene.channels[0]);
    const double psnr = psnr_db(estimate.image, scene.channels[0]);
    std::printf("capture against the scene: PSNR %.2f dB\n", capture_psnr);
    std::printf("Wiener (NSR %.3g): PSNR %.2f dB\n", decode.wiener.nsr, psnr);
    return std::isfinite(psnr) ? 0 : 1;
}

}  // namespace

int main() {
    try {
        return run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pinmask example: %s\n", e.what());
        return 1;
    }
}
