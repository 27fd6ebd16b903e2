#!/usr/bin/python3
"""Refocus on the phone-like camera (1.12 um pixels, f' = 4.4 mm, sensor at 4.2 mm, 530 nm,
designed for u = 0.3 m) at 0.6 m with a scene that fills the frame: `pinmask decode --mask M
--object-distance 0.6m` with its defaults (method auto) against Wiener at its automatic NSR (the
default before the method was chosen from the capture), TV at its automatic weight and TV at the
weight the truth chooses (a grid of lambda relative to the capture's peak). The capture is
rendered with numpy by tests/python/test_refocus.py (phone_capture), not by pinmask: every
pinhole's box spot at its Eq. (3) position at 0.6 m by exact pixel overlap, a 1/f scene over a
grid twice the sensor, linear convolution by FFT, Poisson photons (PEAK electrons at the
brightest pixel) and 2 e- read noise. The sensor is a 504 x 378 window of the phone's (ROWS,
COLS to change it; the test uses 252 x 189). PSNR after gain and offset, 8 px margin.
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
# The capture and the PSNR after gain and offset, as the refocus test renders and scores them.
from test_refocus import phone_capture, phone_flags, psnr_aligned as psnr  # noqa: E402
PM = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build" / "cli" / "pinmask")
ROWS, COLS = int(os.environ.get("ROWS", 378)), int(os.environ.get("COLS", 504))
U = 0.6
PEAK = float(os.environ.get("PEAK", 2000))
LAMBDAS = (3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2)


def run(d, *args):
    r = subprocess.run([PM, *args], cwd=d, capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(r.stderr)
    return r


def main():
    d = tempfile.mkdtemp(prefix="refocus-phone-")
    run(d, "design", *phone_flags(ROWS, COLS), "--save-camera", "cam.camera.json")
    run(d, "generate", "--camera", "cam.camera.json", "--seed", "4", "-o", "m.mask.json")
    mask = json.loads(pathlib.Path(d, "m.mask.json").read_text())
    cap, scene = phone_capture(mask, U, ROWS, COLS, PEAK, 5)
    np.save(pathlib.Path(d, "cap.npy"), cap.astype(np.float32))
    inner = (slice(8, ROWS - 8), slice(8, COLS - 8))
    truth = scene[inner]
    base = ["decode", "cap.npy", "--mask", "m.mask.json", "--object-distance", "0.6m"]

    def quality(*flags):
        run(d, *base, *flags, "-o", "x.npy", "--stats", "s.json")
        method = json.loads(pathlib.Path(d, "s.json").read_text())["method"]
        return psnr(np.load(pathlib.Path(d, "x.npy"))[inner], truth), method

    default, method = quality()
    wiener, _ = quality("--method", "wiener")
    tv_auto, _ = quality("--method", "tv")
    grid_q = {lam: quality("--method", "tv", "--lambda", str(lam * cap.max()))[0]
              for lam in LAMBDAS}
    best = max(grid_q, key=grid_q.get)
    print(f"sensor {COLS} x {ROWS}, peak {PEAK:g} e-: default decode ({method}) {default:.2f} dB, "
          f"wiener at its automatic NSR {wiener:.2f} dB, tv at its automatic weight "
          f"{tv_auto:.2f} dB, tv at the oracle weight {grid_q[best]:.2f} dB (lambda {best:g} x "
          f"the capture's peak): default - oracle {default - grid_q[best]:+.2f} dB")
    for lam, q in grid_q.items():
        print(f"  tv lambda {lam:g} x peak: {q:.2f} dB")


if __name__ == "__main__":
    main()
