#!/usr/bin/python3
"""The comparison of depth costs in docs/depth.md (section 3b), in numpy on the scenes of the
four-camera table (tests/python/depth_scenes.py): the sweep's model is the renderer's own PSF at
each plane (so only the cost differs), 16 planes over the camera's range, 384 x 384, photons
2000, the lowest-cost plane per pixel (no smoothing) and the lowest frame-mean cost.
Costs: tests/python/depth_costs.py.
Run: PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_costs.py [SIZE [WINDOW]]"""
import pathlib
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import depth_costs  # noqa: E402
import depth_scenes as ds  # noqa: E402
import pinmask  # noqa: E402

SIZE = int(sys.argv[1]) if len(sys.argv) > 1 else 384
WINDOW = int(sys.argv[2]) if len(sys.argv) > 2 else 121
STEPS, PHOTONS = 16, 2000.0

KINDS = ("residual", "evidence", "split", "joint")
print(f"| camera | scene | " + " | ".join(f"{k}: within one spacing, frame error (planes)"
                                           for k in KINDS) + " |")
with tempfile.TemporaryDirectory() as tmp:
    for name, (cam, near, far) in ds.CAMERAS.items():
        path = pathlib.Path(tmp) / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=pinmask.Camera(**cam), kernel="box").save(str(path))
        mj = ds.load(path)
        inv = ds.range_inverse(near, far, np.linspace(0, 1, STEPS))
        spacing = abs(inv[1] - inv[0])
        psfs = [ds.exact_psf(mj, 1 / v, SIZE, SIZE) for v in inv]
        for scene in ["two planes", "three planes", "slanted plane", 0.1, 0.5, 0.9]:
            positions = [scene] if isinstance(scene, float) else ds.SCENE_KINDS[scene]
            cap, truth, _, inside, _ = ds.kind_scene(mj, positions, near, far, SIZE, PHOTONS, 1)
            cells = []
            for kind in KINDS:
                c = depth_costs.costs(cap, psfs, kind, WINDOW)
                err = inv[c.argmin(0)][inside] - 1 / truth[inside]
                frame = (abs(inv[c.mean((1, 2)).argmin()] - 1 / truth[inside][0]) / spacing
                         if isinstance(scene, float) and kind != "joint" else None)
                cells.append(f"{100 * np.mean(abs(err) <= spacing):.0f} %" +
                             ("" if frame is None else f", {frame:.1f}"))
            label = f"one plane at {1 / ds.range_inverse(near, far, scene):.3g} m" \
                if isinstance(scene, float) else scene
            print(f"| {name} | {label} | " + " | ".join(cells) + " |", flush=True)
