#!/usr/bin/python3
"""The table of docs/depth.md: `pinmask depthmap` on scenes rendered by the independent numpy
model of tests/python/depth_scenes.py, for the close-range machine-vision camera and the paper's
camera. Run from the repository:
PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_table.py [KERNEL [SMOOTH]]
(build/cli/pinmask must exist; SMOOTH is depthmap's --smooth, its default when absent)."""
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
SMOOTH = ["--smooth", sys.argv[2]] if len(sys.argv) > 2 else []

MV = ds.MACHINE_VISION
ROWS = [("mv", [0.45], 0.4, 2.0), ("mv", [1.5], 0.4, 2.0), ("mv", [0.45, 0.7, 1.5], 0.4, 2.0),
        ("paper", [2.0], 1.0, 10.0), ("paper", [5.0], 1.0, 10.0),
        ("paper", [1.5, 3.0, 8.0], 1.0, 10.0)]

with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    for cam_name, planes, frm, to in ROWS:
        cam = pinmask.Camera(**MV) if cam_name == "mv" else pinmask.paper_camera()
        mask = tmp / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=cam, kernel=KERNEL).save(str(mask))

        def run(capture, frm, to, steps):
            np.save(tmp / "cap.npy", capture.astype(np.float32))
            p = subprocess.run([str(ROOT / "build" / "cli" / "pinmask"), "depthmap",
                                str(tmp / "cap.npy"), "--mask", str(mask), "--from", f"{frm}m",
                                "--to", f"{to}m", "--steps", str(steps), "-o", str(tmp / "o"),
                                "--json", *SMOOTH], capture_output=True, text=True, check=True)
            return tmp / "o", json.loads(p.stdout)

        read = lambda p: np.asarray(pinmask.read_image(str(p))[0]).squeeze()
        r = ds.measure(run, read, mask, planes, frm, to, 16, 384, 2000.0, 1)
        print(f"| {cam_name} | {', '.join(f'{u:g}' for u in planes)} m | {r['rms_m']:.3f} | "
              f"{r['rms_planes']:.2f} | {100 * r['within_spacing']:.0f} % | "
              f"{r['aif_psnr_db']:.2f} | {r['single_best_psnr_db']:.2f} | "
              f"{r['capture_depth_m']:.3f} |", flush=True)
