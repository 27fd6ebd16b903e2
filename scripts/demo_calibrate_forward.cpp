// The demo's forward model (scripts/demo-calibrate), built by CMake as
// build/scripts/demo-calibrate-forward; not part of the pinmask product surface.
//   demo-calibrate-forward MASK OUTDIR ROTATION_DEG PITCH_SCALE MISSING LEAK SNR_DB SEED
//     writes into OUTDIR, on the mask camera's sensor frame:
//       point.tiff       a point source seen through a perturbed copy of the mask: rotated,
//                        pitch scaled, MISSING pinholes (of the tiled mask) closed, the opaque
//                        film transmitting LEAK of an open cell's light, Gaussian noise at SNR_DB
//                        (peak / sigma);
//       scene.tiff       the test scene ("natural", seeded);
//       capture.tiff     the scene through the same perturbed mask (circular convolution over
//                        the frame with the perturbed PSF, deconvwnr centring) plus noise;
//       design-psf.tiff  the design's full-frame PSF: the same rendering without perturbations.
//   demo-calibrate-forward --psnr ESTIMATE TRUTH
//     prints the PSNR (dB) of ESTIMATE against TRUTH at the best integer shift within 12 px
//     (a PSF's absolute position only shifts the decoded image).
// The PSFs are the mask's kernel (design/psf/psf mask_kernel) placed at sub-pixel spot positions by
// decode/calibrate/subpixel add_kernel; the lattice is centred in the frame.
#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include "core/fft/fft.hpp"
#include "core/image/image_io.hpp"
#include "decode/calibrate/subpixel.hpp"
#include "design/psf/psf.hpp"
#include "io/mask_json.hpp"
#include "optimize/simulate/image_quality.hpp"
#include "optimize/simulate/scenes.hpp"

using namespace pinmask;

namespace {

Plane render(const Mask& m, const Kernel& k, double rot_deg, double scale, int missing,
             std::mt19937_64& rng) {
    const int rows = m.camera.sensor_rows, cols = m.camera.sensor_cols, n = m.pattern.n;
    const double p = m.psf.pixels_per_cell * scale, t = rot_deg * M_PI / 180.0;
    const int mr = n * m.pattern.tiles_rows, mc = n * m.pattern.tiles_cols;
    std::vector<Cell> open;
    for (int tr = 0; tr < m.pattern.tiles_rows; ++tr)
        for (int tc = 0; tc < m.pattern.tiles_cols; ++tc)
            for (const Cell& c : m.pattern.pinholes)
                open.push_back({c.row + tr * n, c.col + tc * n});
    std::shuffle(open.begin(), open.end(), rng);
    open.erase(open.begin(), open.begin() + std::min<std::size_t>(missing, open.size()));
    double ky = 0, kx = 0;
    calibrate::centroid(k.values, ky, kx);
    Plane psf = Plane::Zero(rows, cols);
    for (const Cell& c : open) {
        const double u = c.col - 0.5 * (mc - 1), v = c.row - 0.5 * (mr - 1);
        // Counter-clockwise on screen with rows running down for t > 0 (the project's sense).
        const double x = 0.5 * (cols - 1) + p * (std::cos(t) * u + std::sin(t) * v);
        const double y = 0.5 * (rows - 1) + p * (-std::sin(t) * u + std::cos(t) * v);
        calibrate::add_kernel(psf, k.values, ky, kx, y, x, 1.0);
    }
    return psf;
}

Plane convolve(const Plane& x, const Plane& psf) {
    const int r = static_cast<int>(x.rows()), c = static_cast<int>(x.cols());
    Fft2 fft(r, c);
    const ComplexPlane X = fft.forward(x), H = fft.forward(circshift(psf, -(r / 2), -(c / 2)));
    return fft.inverse((X * H).eval());
}

void add_noise(Plane& p, double snr_db, std::mt19937_64& rng) {
    std::normal_distribution<double> nd(0.0, p.maxCoeff() / std::pow(10.0, snr_db / 20.0));
    for (auto& v : p.reshaped()) v += nd(rng);
}

}  // namespace

int main(int argc, char** argv) try {
    if (argc == 4 && std::string(argv[1]) == "--psnr") {
        const Plane est = read_image(argv[2]).image.channels.at(0);
        const Plane truth = read_image(argv[3]).image.channels.at(0);
        double best = -1e300;
        for (int dr = -12; dr <= 12; ++dr)
            for (int dc = -12; dc <= 12; ++dc)
                best = std::max(best, psnr_db(circshift(est, dr, dc), truth));
        std::cout << best << "\n";
        return 0;
    }
    if (argc != 9) {
        std::cerr << "usage: demo-calibrate-forward MASK OUTDIR ROTATION_DEG PITCH_SCALE MISSING "
                     "LEAK SNR_DB SEED | --psnr ESTIMATE TRUTH\n";
        return 2;
    }
    const Mask mask = io::read_mask_file(argv[1]);
    const std::string out = argv[2];
    const double rot = std::stod(argv[3]), scale = std::stod(argv[4]), leak = std::stod(argv[6]),
                 snr = std::stod(argv[7]);
    const int missing = std::stoi(argv[5]);
    std::mt19937_64 rng(std::stoull(argv[8]));
    const Kernel k = mask_kernel(mask);
    std::mt19937_64 none(0);
    const Plane design = render(mask, k, 0.0, 1.0, 0, none);
    Plane truth = render(mask, k, rot, scale, missing, rng);
    // Leak: every pixel of the (perturbed) mask's footprint gets LEAK of an open cell's light
    // spread over a cell's area.
    Plane point = truth;
    {
        const double p = mask.psf.pixels_per_cell * scale, t = rot * M_PI / 180.0;
        const int mr = mask.pattern.n * mask.pattern.tiles_rows;
        const int mc = mask.pattern.n * mask.pattern.tiles_cols;
        for (int r = 0; r < point.rows(); ++r)
            for (int c = 0; c < point.cols(); ++c) {
                const double dx = c - 0.5 * (point.cols() - 1), dy = r - 0.5 * (point.rows() - 1);
                const double u = (std::cos(t) * dx + std::sin(t) * dy) / p;
                const double v = (-std::sin(t) * dx + std::cos(t) * dy) / p;
                if (std::abs(u) <= 0.5 * mc && std::abs(v) <= 0.5 * mr)
                    point(r, c) += leak / (p * p);
            }
    }
    point *= 1000.0;  // counts
    add_noise(point, snr, rng);
    const Plane scene =
        make_scene(scene_from_name("natural"), mask.camera.sensor_rows, mask.camera.sensor_cols)
            .channels.at(0);
    Plane capture = convolve(scene, truth / truth.sum());
    add_noise(capture, snr, rng);
    write_tiff(out + "/point.tiff", Image(point), SampleFormat::kFloat32);
    write_tiff(out + "/scene.tiff", Image(scene), SampleFormat::kFloat32);
    write_tiff(out + "/capture.tiff", Image(capture), SampleFormat::kFloat32);
    write_tiff(out + "/design-psf.tiff", Image(design / design.sum()), SampleFormat::kFloat32);
    return 0;
} catch (const std::exception& e) {
    std::cerr << "demo-calibrate-forward: " << e.what() << "\n";
    return 2;
}
