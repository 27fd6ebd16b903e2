"""An independent forward model for the automatic-weight table of docs/decoding.md and its test
(tests/python/test_autoreg.py): four cameras, photographs from Debian's python3-skimage data
set, captures rendered here in numpy (PSFs drawn as geometric box spots from the pinhole cells
and the camera by depth_scenes.exact_psf, convolution by FFT, Poisson photon noise and Gaussian
read noise), never by pinmask's simulate or PSF code.

Cameras (docs/design.md section 2: pitch = d M(u) / w, M(u) = 1 - f/f' + f/u):
- paper: the paper's prototype (f' 120 mm, f 55 mm, u 6 m, 30 um pixels), 16 x 16 cells of
  8 px, K = 20: a 128 x 128 period, cyclic model;
- nir-mv: a near-infrared machine-vision camera (f' 25 mm, f 20 mm, u 0.5 m, 3.45 um pixels),
  20 x 20 cells of 6 px, K = 24: a 120 x 120 period, cyclic;
- phone: a 1.12 um phone module (f' 4.4 mm, sensor at 4.2 mm, 530 nm, u 0.3 m), 8 x 8 cells of
  16 px, K = 10, cyclic;
- lensless: a lensless pinhole array (no lens, sensor 2 mm behind the film, u 0.5 m, 5 um
  pixels), 32 x 32 cells of 3 px with K = 15 pinholes, one pattern over a 96 x 96 sensor:
  linear model (zero-padded convolution and a crop to the sensor).
The pinhole cells are a seeded random choice (numpy's default_rng), not a pinmask design.
"""
import pathlib

import numpy as np

import depth_scenes as ds

PHOTOS = pathlib.Path("/usr/lib/python3/dist-packages/skimage/data")


def _camera(lens_focal_m, sensor_distance_m, u, pixel_m, n, n_px, k, seed):
    m = 1.0 - sensor_distance_m / lens_focal_m + sensor_distance_m / u
    rng = np.random.default_rng(seed)
    cells = rng.choice(n * n, size=k, replace=False)
    optics = dict(lens_focal_m=lens_focal_m, sensor_distance_m=sensor_distance_m,
                  pixel_pitch_m=pixel_m, pinhole_m=n_px * pixel_m / m)
    pattern = dict(n=n, tiles=[1, 1], pinholes=[[int(c) // n, int(c) % n] for c in cells])
    psf = ds.exact_psf(dict(optics=optics, pattern=pattern), u, n * n_px, n * n_px)
    return psf / psf.sum()


# name -> (model, PSF); every PSF is normalised to unit sum.
def cameras(seed=0):
    return {
        "paper": ("cyclic", _camera(0.120, 0.055, 6.0, 30e-6, 16, 8, 20, 1 + seed)),
        "nir-mv": ("cyclic", _camera(0.025, 0.020, 0.5, 3.45e-6, 20, 6, 24, 2 + seed)),
        "phone": ("cyclic", _camera(0.0044, 0.0042, 0.3, 1.12e-6, 8, 16, 10, 3 + seed)),
        "lensless": ("linear", _camera(1e9, 0.002, 0.5, 5e-6, 32, 3, 15, 4 + seed)),
    }


def photo(name, rows, cols):
    """The photograph as grey values in [0, 1], its central square resized to rows x cols."""
    from skimage import color, io, transform
    a = io.imread(PHOTOS / name)
    a = a.astype(float) / (255.0 if a.dtype == np.uint8 else a.max())
    if a.ndim == 3:
        a = color.rgb2gray(a[..., :3])
    s = min(a.shape)
    r0, c0 = (a.shape[0] - s) // 2, (a.shape[1] - s) // 2
    return transform.resize(a[r0:r0 + s, c0:c0 + s], (rows, cols), order=1, anti_aliasing=True)


def render(name, model, psf, photons, read_e, seed, sensor=96):
    """(capture in electrons, truth in [0, 1] on the decoded window, electrons per unit).

    cyclic: the scene is one period (the PSF's size), circularly convolved. linear: the scene
    covers the sensor plus the PSF's reach, convolved fully and cropped to the sensor window
    (the decoded window: pinmask's linear model reports the scene under the sensor)."""
    rng = np.random.default_rng(seed)
    pr, pc = psf.shape
    if model == "cyclic":
        truth = photo(name, pr, pc)
        clean = ds.blur(truth, psf)
    else:
        cr, cc = pr // 2, pc // 2
        scene = photo(name, sensor + pr - 1, sensor + pc - 1)
        # capture(i) = sum_r psf(r) scene(i + cr - r + m), m = pr - 1 - cr: the 'valid' part.
        full = np.fft.irfft2(np.fft.rfft2(scene, s=(sensor + 2 * pr - 2, sensor + 2 * pc - 2)) *
                             np.fft.rfft2(psf, s=(sensor + 2 * pr - 2, sensor + 2 * pc - 2)),
                             s=(sensor + 2 * pr - 2, sensor + 2 * pc - 2))
        clean = full[pr - 1:pr - 1 + sensor, pc - 1:pc - 1 + sensor]
        m_r, m_c = pr - 1 - cr, pc - 1 - cc
        truth = scene[m_r:m_r + sensor, m_c:m_c + sensor]
    electrons = rng.poisson(np.clip(clean, 0, None) * photons) + rng.normal(0, read_e, clean.shape)
    return electrons, truth, photons


def psnr(estimate, truth):
    return 10 * np.log10(1.0 / np.mean((estimate - truth) ** 2))
