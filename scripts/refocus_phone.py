#!/usr/bin/python3
"""Refocus on the phone-like camera (1.12 um pixels, f' = 4.4 mm, sensor at 4.2 mm, 530 nm,
designed for u = 0.3 m) at 0.6 m with a scene that fills the frame: `pinmask decode --mask M
--object-distance 0.6m` with its defaults against TV at the weight the truth chooses (a grid of
lambda relative to the capture's peak) and TV at its automatic weight. The capture is rendered
here with numpy, not by pinmask: every pinhole's box spot at its Eq. (3) position at 0.6 m by
exact pixel overlap, a 1/f scene over a grid twice the sensor, linear convolution by FFT, Poisson
photons (PEAK electrons at the brightest pixel) and 2 e- read noise. The sensor is a 504 x 378
window of the phone's (ROWS, COLS to change it). PSNR after gain and offset, 8 px margin.
Run from the repository: /usr/bin/python3 scripts/refocus_phone.py [PINMASK_EXE]"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
# The box spot by exact pixel overlap and the PSNR after gain and offset, as the refocus test
# renders and scores its capture.
from test_refocus import box_overlap, psnr_aligned as psnr  # noqa: E402
PM = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build" / "cli" / "pinmask")
F, FL, W = 4.2e-3, 4.4e-3, 1.12e-6
ROWS, COLS = int(os.environ.get("ROWS", 378)), int(os.environ.get("COLS", 504))
U = 0.6
PEAK = float(os.environ.get("PEAK", 2000))
LAMBDAS = (3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2)
CAMERA = ["--pixel-pitch", "1.12um", "--sensor", f"{COLS}x{ROWS}", "--lens-focal", "4.4mm",
          "--sensor-distance", "4.2mm", "--object-distance", "0.3m", "--wavelength", "530nm"]


def run(d, *args):
    r = subprocess.run([PM, *args], cwd=d, capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(r.stderr)
    return r


def true_psf(mask, u):
    p = mask["pattern"]
    n, (tr, tc) = p["n"], p["tiles"]
    pitch = mask["optics"]["pinhole_m"] * (1 - F / FL + F / u) / W  # px per cell at u
    psf = np.zeros((ROWS, COLS))
    for ti in range(tr):
        for tj in range(tc):
            for r, c in p["pinholes"]:
                cy = ROWS / 2 + (ti * n + r + 0.5 - n * tr / 2) * pitch
                cx = COLS / 2 + (tj * n + c + 0.5 - n * tc / 2) * pitch
                psf += np.outer(box_overlap(cy, pitch, ROWS), box_overlap(cx, pitch, COLS))
    return psf / psf.sum()


def scene(shape, rng):
    fy = np.fft.fftfreq(shape[0])[:, None]
    fx = np.fft.rfftfreq(shape[1])[None, :]
    s = np.fft.rfft2(rng.standard_normal(shape)) / np.maximum(np.hypot(fy, fx), 1.0 / max(shape))
    x = np.fft.irfft2(s, shape)
    return (x - x.min()) / (x.max() - x.min())


def main():
    d = tempfile.mkdtemp(prefix="refocus-phone-")
    run(d, "design", *CAMERA, "--save-camera", "cam.camera.json")
    run(d, "generate", "--camera", "cam.camera.json", "--seed", "4", "-o", "m.mask.json")
    mask = json.loads(pathlib.Path(d, "m.mask.json").read_text())
    psf = true_psf(mask, U)
    rng = np.random.default_rng(5)
    grid = (2 * ROWS, 2 * COLS)
    x = scene(grid, rng)
    pad = np.zeros(grid)
    pad[:ROWS, :COLS] = psf
    pad = np.roll(pad, (-(ROWS // 2), -(COLS // 2)), (0, 1))
    y = np.fft.irfft2(np.fft.rfft2(x) * np.fft.rfft2(pad), grid)
    r0, c0 = (grid[0] - ROWS) // 2, (grid[1] - COLS) // 2
    cap = y[r0:r0 + ROWS, c0:c0 + COLS]
    cap = rng.poisson(np.maximum(cap / cap.max() * PEAK, 0)) + rng.normal(0, 2, cap.shape)
    np.save(pathlib.Path(d, "cap.npy"), cap.astype(np.float32))
    inner = (slice(8, ROWS - 8), slice(8, COLS - 8))
    truth = x[r0:r0 + ROWS, c0:c0 + COLS][inner]
    base = ["decode", "cap.npy", "--mask", "m.mask.json", "--object-distance", "0.6m"]

    def quality(*flags):
        run(d, *base, *flags, "-o", "x.npy")
        return psnr(np.load(pathlib.Path(d, "x.npy"))[inner], truth)

    default = quality()
    tv_auto = quality("--method", "tv")
    grid_q = {lam: quality("--method", "tv", "--lambda", str(lam * cap.max())) for lam in LAMBDAS}
    best = max(grid_q, key=grid_q.get)
    print(f"sensor {COLS} x {ROWS}, peak {PEAK:g} e-: default decode {default:.2f} dB, "
          f"tv at its automatic weight {tv_auto:.2f} dB, tv at the oracle weight "
          f"{grid_q[best]:.2f} dB (lambda {best:g} x the capture's peak)")
    for lam, q in grid_q.items():
        print(f"  tv lambda {lam:g} x peak: {q:.2f} dB")


if __name__ == "__main__":
    main()
