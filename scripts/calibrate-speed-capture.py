#!/usr/bin/env python3
"""Renders the issue's NIR point-source capture on the full 1920 x 1200 sensor for timing
`pinmask calibrate` (docs/calibration.md, Speed): writes OUT/nir.mask.json and OUT/nir-point.npy
(OUT is created when it does not exist).
Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/calibrate-speed-capture.py OUT
then: time build/cli/pinmask calibrate OUT/nir-point.npy --mask OUT/nir.mask.json -o OUT/cal"""
import pathlib, sys

import numpy as np
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "python"))
import pinmask
from test_calibrate import pinhole_profile
cam = pinmask.Camera(object_distance_m=1.2, lens_focal_m=0.075, sensor_distance_m=0.045,
                     wavelength_m=850e-9, pixel_pitch_m=5.86e-6, pinhole_m=455.4e-6,
                     sensor_cols=1920, sensor_rows=1200)
m = pinmask.generate(family="random", grid=10, holes=15, spacing=2, tiles=6, seed=3, camera=cam,
                     pixels_per_cell=34)
inv_z = 1/0.045 - 1/0.075 + 1/1.2
pitch = 0.045*inv_z*455.4e-6/5.86e-6
a = 455.4e-6*5.86e-6/(850e-9*0.045); n_f = 455.4e-6**2*inv_z/(4*850e-9)
R, C = 1200, 1920
nt = 60
t = np.deg2rad(1.0); ct, st = np.cos(t), np.sin(t)
vx = np.linspace(-400, 400, 800*8+1); prof = a*pinhole_profile(n_f, a*vx)
img = np.zeros((R, C)); rows = np.arange(R); cols = np.arange(C)
for tr in range(6):
    for tc in range(6):
        for (r, c) in m.pattern.pinholes:
            cr, cc = r + 10*tr + 0.5 - nt/2, c + 10*tc + 0.5 - nt/2
            x = (C-1)/2 + pitch*(ct*cc + st*cr); y = (R-1)/2 + pitch*(-st*cc + ct*cr)
            if not (-300 < x < C+300 and -300 < y < R+300): continue
            px = np.interp(cols - x, vx, prof, left=0, right=0)
            py = np.interp(rows - y, vx, prof, left=0, right=0)
            img += 5e5*np.outer(py, px)
rng = np.random.default_rng(1)
cap = np.round(rng.poisson(img + 20.0) + rng.normal(0, 3, img.shape))
out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
m.save(out / "nir.mask.json")
np.save(out / "nir-point.npy", cap)
print("rendered", cap.shape)
