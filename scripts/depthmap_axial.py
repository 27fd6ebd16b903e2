#!/usr/bin/python3
"""Axial resolution of the plane sweep (docs/depth.md): a point source on the axis at known
distances u0, rendered by the independent numpy model (tests/python/depth_scenes.py: its PSF at
u0 times 20000 photo-electrons in all, photon noise), swept by `pinmask depthmap` over 41 planes
equally spaced in 1/u over 1/u0 +- 4 one-pixel steps (below). The depth estimate is the
whole-capture figure capture_depth_m (the frame-mean cost's minimum, parabola-refined). Per u0,
DRAWS noise draws: the estimates' mean (bias against u0) and standard deviation; the FWHM of the
estimate's profile is 2.355 sigma (a Gaussian's). Beside them the one-pixel figure: the
pattern's extent N_t d grows by f N_t d |d(1/u)| / w pixels, one pixel at d(1/u) = w / (f N_t d),
i.e. du = u0^2 w / (f N_t d), and the Cramer-Rao bound of optimize/metrics/depth_fisher
(pinmask.depth_fisher: the noise floor of any unbiased estimate, as a FWHM 2.355 sigma). Writes docs/depthmap_axial.png (with a kernel argument KERNEL:
docs/depthmap_axial_KERNEL.png) and prints the table.
Run from the repository: PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_axial.py [KERNEL]"""
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import depth_scenes as ds  # noqa: E402
import pinmask  # noqa: E402

# The masks' kernel model: the first argument (default auto, the mask's own choice; "box" draws
# the spots as the numpy scene model does, so the sweep's model matches the scene exactly).
KERNEL = sys.argv[1] if len(sys.argv) > 1 else "auto"

MV = ds.MACHINE_VISION
CAMERAS = {"machine vision (f' 25 mm, f 20 mm)": (MV, [0.3, 0.5, 0.8, 1.2, 2.0, 3.0]),
           "paper (f' 120 mm, f 55 mm)": (None, [0.6, 1.0, 2.0, 4.0, 6.0, 10.0])}
SIZE, STEPS = 384, 41


DRAWS = 5


rows = []
with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    for name, (cam, distances) in CAMERAS.items():
        camera = pinmask.Camera(**cam) if cam else pinmask.paper_camera()
        mask = tmp / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=camera, kernel=KERNEL).save(str(mask))
        mj = ds.load(mask)
        o = mj["optics"]
        nt_d = mj["pattern"]["n"] * mj["pattern"]["tiles"][1] * o["pinhole_m"]
        one_px = o["pixel_pitch_m"] / (o["sensor_distance_m"] * nt_d)  # d(1/u), 1/m
        rng = np.random.default_rng(5)
        for u0 in distances:
            clean = ds.exact_psf(mj, u0, SIZE, SIZE) * 20000.0
            half = 4 * one_px
            lo_inv = max(1 / u0 - half, 1e-6)
            hi_inv = min(1 / u0 + half, 1 / (1.05 * o["lens_focal_m"]))
            est = []
            for _ in range(DRAWS):
                np.save(tmp / "cap.npy", rng.poisson(clean).astype(np.float32))
                p = subprocess.run([str(ROOT / "build" / "cli" / "pinmask"), "depthmap",
                                    str(tmp / "cap.npy"), "--mask", str(mask), "--from",
                                    f"{1 / hi_inv}", "--to", f"{1 / lo_inv}", "--steps",
                                    str(STEPS), "--window", "31", "-o", str(tmp / "o"),
                                    "--json"], capture_output=True, text=True, check=True)
                est.append(json.loads(p.stdout)["capture_depth_m"])
            mean, sd = float(np.mean(est)), float(np.std(est, ddof=1))
            bias_px = (1 / mean - 1 / u0) / one_px
            crb = pinmask.depth_fisher(str(mask), u0, photons=20000.0, rows=SIZE,
                                       cols=SIZE)["crb_distance_m"]
            rows.append((name, u0, mean, 2.355 * sd, abs(mean - u0), u0 * u0 * one_px,
                         2.355 * crb))
            print(f"| {name} | {u0:g} | {mean:.4f} | {mean - u0:+.4f} ({bias_px:+.2f} px) | "
                  f"{2.355 * sd:.5f} | {2.355 * crb:.5f} | {u0 * u0 * one_px:.4f} |",
                  flush=True)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, ax = plt.subplots(figsize=(7, 4.5), dpi=110)
for name, marker in zip(CAMERAS, ["o", "s"]):
    r = [x for x in rows if x[0] == name]
    u = np.array([x[1] for x in r])
    line = ax.loglog(u, [x[3] for x in r], marker, label=f"{name}: FWHM of the estimates")[0]
    ax.loglog(u, [max(x[4], 1e-5) for x in r], marker, mfc="none", color=line.get_color(),
              label=f"{name}: |bias| of the mean")
    ax.loglog(u, [x[5] for x in r], "-", color=line.get_color(),
              label=f"{name}: one pixel of pattern change")
    ax.loglog(u, [x[6] for x in r], ":", color=line.get_color(),
              label=f"{name}: Cramer-Rao bound (FWHM)")
ax.set_xlabel("object distance u0 (m)")
ax.set_ylabel("axial error (m)")
ax.set_title(f"pinmask depthmap: a point source on the axis, {KERNEL} kernel "
             "(scripts/depthmap_axial.py)",
             fontsize=9)
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(ROOT / "docs" / ("depthmap_axial.png" if KERNEL == "auto"
                             else f"depthmap_axial_{KERNEL}.png"))
