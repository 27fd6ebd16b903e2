#!/usr/bin/python3
"""The depth map's confidence as a probability (docs/depth.md section 3c): its fit and its
reliability diagram. pinmask.depthmap with its defaults (window 121, smoothing 8) over 16 planes
spanning each camera's range, on the scenes of tests/python/depth_scenes.py (the four SCENE_KINDS
and one plane at range positions 0.1, 0.5, 0.9; 384 x 384, photons 2000, box-kernel masks, seed
3), every pixel inside the border counted, a flat pixel as a miss (its depth cannot be read).
  fit:     scene seed 1, machine-vision and visible 35 mm cameras only: the share within one plane
           spacing in bins of the result's cost_margin 0.05 wide, and its non-decreasing fit
           (the knots of decode/depthmap/calibrated_confidence, capped there at 0.95);
  report:  scene seed 2, the paper and phone cameras (never fitted on): among the pixels at
           confidence >= c, their share and the share within one spacing; per confidence bin
           the mean confidence and the share within; the flat region's median confidence.
Run from the repository: PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_reliability.py
[fit|report] (about 4 minutes each at load 4)."""
import pathlib
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import depth_scenes as ds  # noqa: E402
import pinmask  # noqa: E402

KINDS = list(ds.SCENE_KINDS) + [0.1, 0.5, 0.9]
FIT = (["machine vision", "visible 35 mm"], 1)
REPORT = (["paper", "phone"], 2)


def pixels(cameras, seed, tmp):
    """Per camera and scene: (confidence, cost margin, within one spacing) of the pixels inside
    the border, and the flat region's confidences."""
    out = []
    for name in cameras:
        cam, near, far = ds.CAMERAS[name]
        path = pathlib.Path(tmp) / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=pinmask.Camera(**cam), kernel="box").save(str(path))
        mj = ds.load(path)
        for kind in KINDS:
            positions = [kind] if isinstance(kind, float) else ds.SCENE_KINDS[kind]
            cap, truth, _, inside, flat = ds.kind_scene(mj, positions, near, far, 384, 2000.0,
                                                        seed, flat_right=(kind == "half flat"))
            r = pinmask.depthmap(cap, str(path), from_m=near, to_m=far, steps=16)
            spacing = (1 / near - 1 / far) / 15
            hit = (abs(1 / r["depth_m"] - 1 / truth) <= spacing) & ~flat
            out.append((name, kind, r["confidence"][inside], r["cost_margin"][inside],
                        hit[inside], r["confidence"][flat]))
    return out


def fit(rows):
    margin = np.concatenate([r[3] for r in rows])
    hit = np.concatenate([r[4] for r in rows])
    edges = np.arange(0.0, 0.55, 0.05)
    rate, weight = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        s = (margin >= a) & (margin < b)
        rate.append(hit[s].mean() if s.any() else 0.0)
        weight.append(max(int(s.sum()), 1))
    # Pool adjacent violators: the non-decreasing fit of the shares, weighted by the pixels.
    blocks = []
    for y, w in zip(rate, weight):
        blocks.append([y * w, w, 1])
        while len(blocks) > 1 and blocks[-2][0] / blocks[-2][1] > blocks[-1][0] / blocks[-1][1]:
            s, w2, n = blocks.pop()
            blocks[-1] = [blocks[-1][0] + s, blocks[-1][1] + w2, blocks[-1][2] + n]
    iso = [s / w for s, w, n in blocks for _ in range(n)]
    print("| margin bin centre | pixels | share within one spacing | non-decreasing fit |")
    print("|---|---|---|---|")
    for a, b, y, w, f in zip(edges[:-1], edges[1:], rate, weight, iso):
        print(f"| {(a + b) / 2:.3f} | {w} | {y:.3f} | {f:.3f} |")


def report(rows):
    conf = np.concatenate([r[2] for r in rows])
    hit = np.concatenate([r[4] for r in rows])
    print("| c | share of pixels at confidence >= c | within one spacing among them |")
    print("|---|---|---|")
    for c in (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9):
        s = conf >= c
        print(f"| {c:.1f} | {s.mean():.3f} | {hit[s].mean() if s.any() else float('nan'):.3f} |")
    print()
    print("| confidence bin | share of pixels | mean confidence | within one spacing |")
    print("|---|---|---|---|")
    for a, b in ((0.0, 0.3), (0.3, 0.5), (0.5, 0.7), (0.7, 0.9), (0.9, 1.01)):
        s = (conf >= a) & (conf < b)
        if s.any():
            print(f"| {a:.1f}-{min(b, 1.0):.1f} | {s.mean():.3f} | {conf[s].mean():.3f} | "
                  f"{hit[s].mean():.3f} |")
    for name, kind, _, _, _, flat in rows:
        if flat.size:
            print(f"flat region, {name}: median confidence {np.median(flat):.3f}")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "report"
    cameras, seed = FIT if what == "fit" else REPORT
    with tempfile.TemporaryDirectory() as tmp:
        rows = pixels(cameras, seed, tmp)
    fit(rows) if what == "fit" else report(rows)
