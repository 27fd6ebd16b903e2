"""The real DiffuserCam captures (PINMASK_SHARED_DIR/data/real, their READMEs) and a reference
decode of each written here in numpy, independent of pinmask's decoders: the source's own
preprocessing (the DiffuserCam tutorial: a background off capture and PSF, 2 x 2 box
averaging, each divided by its L2 norm) and its gradient-descent notebook's solver (FISTA with
x >= 0 on the linear model, the PSF's centre at the origin, step 1.8 / max|H|^2), which the
data's README found to give the clean hand. Used by scripts/real_defaults_table.py and
tests/python/test_real_defaults.py."""
import os
import pathlib

import numpy as np
from PIL import Image

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]


def real_dir():
    shared = pathlib.Path(os.environ.get("PINMASK_SHARED_DIR", SOURCE_DIR.parent / "shared"))
    return shared / "data" / "real"


# name: (capture, PSF, the source's background: "corner" (the PSF's rows/cols 5..14, off both)
# or (capture counts, PSF value) (the 3D data's camera bias; the LCAV PSF's floor, its median)).
CAPTURES = {
    "hand": ("waller-lab-diffusercam-tutorial/rawdata_hand_sample.tif",
             "waller-lab-diffusercam-tutorial/psf_sample.tif", "corner"),
    "usaf": ("waller-lab-diffusercam-3d/example_raw.png",
             "waller-lab-diffusercam-3d/psf_stack/psf18.tiff", "bias"),
}


def available():
    return all((real_dir() / c).is_file() and (real_dir() / p).is_file()
               for c, p, _ in CAPTURES.values())


def paths(name):
    c, p, _ = CAPTURES[name]
    return str(real_dir() / c), str(real_dir() / p)


def load(name):
    """(capture, psf) as float arrays, read with PIL (not pinmask's readers)."""
    c, p = paths(name)
    return (np.asarray(Image.open(c), dtype=float), np.asarray(Image.open(p), dtype=float))


def box_downsample(a, rounds):
    for _ in range(rounds):
        r, c = a.shape[0] // 2 * 2, a.shape[1] // 2 * 2
        a = a[:r, :c].reshape(r // 2, 2, c // 2, 2).mean(axis=(1, 3))
    return a


def preprocess(name, rounds):
    """The source's preprocessing: (capture, psf), each of unit L2 norm."""
    cap, psf = load(name)
    if CAPTURES[name][2] == "corner":
        b = psf[5:15, 5:15].mean()
        cap, psf = cap - b, psf - b
    else:
        cap, psf = cap - 100.0, np.maximum(psf - np.median(psf), 0.0)
    cap, psf = box_downsample(cap, rounds), box_downsample(psf, rounds)
    return cap / np.linalg.norm(cap), psf / np.linalg.norm(psf)


def fista_nonneg(cap, psf, iters=300):
    """Non-negative FISTA on the linear model: the capture window centred in a grid of twice its
    size, the PSF's element (rows // 2, cols // 2) at the origin; the window of the estimate."""
    R, C = cap.shape
    W = (2 * R, 2 * C)
    pad = np.zeros(W)
    pad[:psf.shape[0], :psf.shape[1]] = psf
    H = np.fft.rfft2(np.roll(pad, (-(psf.shape[0] // 2), -(psf.shape[1] // 2)), axis=(0, 1)))
    r0, c0 = (W[0] - R) // 2, (W[1] - C) // 2
    win = (slice(r0, r0 + R), slice(c0, c0 + C))

    def forward(x):
        return np.fft.irfft2(H * np.fft.rfft2(x), W)[win]

    def adjoint(y):
        z = np.zeros(W)
        z[win] = y
        return np.fft.irfft2(np.conj(H) * np.fft.rfft2(z), W)

    step = 1.8 / np.max(np.abs(H) ** 2)
    x = np.zeros(W)
    v, t = x.copy(), 1.0
    for _ in range(iters):
        x_new = np.maximum(v - step * adjoint(forward(v) - cap), 0.0)
        t_new = (1 + np.sqrt(1 + 4 * t * t)) / 2
        v = x_new + (t - 1) / t_new * (x_new - x)
        x, t = x_new, t_new
    return x[win]


def psnr_fit(estimate, reference):
    """PSNR (dB, peak the reference's range) of the estimate after the least-squares gain and
    offset onto the reference: decodes in different units compare as displayed."""
    e, r = np.ravel(estimate).astype(float), np.ravel(reference).astype(float)
    a = np.vstack([e, np.ones_like(e)]).T
    coef, *_ = np.linalg.lstsq(a, r, rcond=None)
    mse = np.mean((a @ coef - r) ** 2)
    return 10 * np.log10((r.max() - r.min()) ** 2 / mse)
