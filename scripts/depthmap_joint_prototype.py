#!/usr/bin/python3
"""A numpy prototype of a joint image/depth refinement for the depth map (docs/depth.md section
3b): for labels l (a plane per pixel), the image x of the whole scene solves
    min_x |y - sum_j K_j (*) (m_j . x)|^2 + lam |grad x|^2,   m_j = [l == j]
(conjugate gradients, periodic), and the labels are scored by that minimum: every labelling has
the same unknowns, so unlike the per-plane residual the score does not favour a PSF that fits
more. The phone camera's two-plane scene of tests/python/depth_scenes.py (box-kernel mask, seed
3; 192 x 192, scene seed 3, 16 planes over 0.2-1 m). Prints the score of the sweep's labels
(pinmask.depthmap's defaults), the true labels and each band's plane over the whole frame, then
moves blocks (not pixels) greedily:
  sweep:   from the sweep's labels, blocks of 24 px, each tried at its plane +-1 and +-2;
  single:  from the best single plane, blocks of 48 px, each tried at every plane.
Run from the repository: PYTHONPATH=build/python /usr/bin/python3
scripts/depthmap_joint_prototype.py [sweep|single] (about 3 and 2 minutes)."""
import pathlib
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import depth_scenes as ds  # noqa: E402
import pinmask  # noqa: E402

S, STEPS, LAM = 192, 16, 1e-3


def main(start):
    cam, near, far = ds.CAMERAS["phone"]
    m = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=pinmask.Camera(**cam), kernel="box")
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "m.mask.json"
        m.save(str(path))
        mj = ds.load(path)
    cap, truth, _, inside, _ = ds.kind_scene(mj, ds.SCENE_KINDS["two planes"], near, far, S,
                                             2000.0, 3)
    inv = ds.range_inverse(near, far, np.linspace(0, 1, STEPS))
    spacing = abs(inv[1] - inv[0])
    otf = [np.fft.rfft2(np.fft.ifftshift(ds.exact_psf(mj, 1 / v, S, S))) for v in inv]

    def forward(x, lab, planes):
        return sum(np.fft.irfft2(otf[j] * np.fft.rfft2(x * (lab == j)), s=(S, S)) for j in planes)

    def adjoint(y, lab, planes):
        f = np.fft.rfft2(y)
        return sum(np.fft.irfft2(np.conj(otf[j]) * f, s=(S, S)) * (lab == j) for j in planes)

    def lap(x):
        return 4 * x - sum(np.roll(x, s, a) for s in (1, -1) for a in (0, 1))

    def score(lab, x0=None, its=40):
        planes = np.unique(lab)
        normal = lambda v: adjoint(forward(v, lab, planes), lab, planes) + LAM * lap(v)
        x = np.zeros((S, S)) if x0 is None else x0.copy()
        r = adjoint(cap, lab, planes) - normal(x)
        p, rs = r.copy(), np.sum(r * r)
        for _ in range(its):
            ap = normal(p)
            a = rs / np.sum(p * ap)
            x, r = x + a * p, r - a * ap
            rn = np.sum(r * r)
            p, rs = r + rn / rs * p, rn
        res = cap - forward(x, lab, planes)
        return x, float(np.sum(res ** 2) + LAM * np.sum(x * lap(x)))

    def within(lab):
        return float(np.mean(abs(inv[lab][inside] - 1 / truth[inside]) <= spacing))

    sweep = pinmask.depthmap(cap, m, from_m=near, to_m=far, steps=STEPS)["label"].astype(int)
    true = np.argmin(abs(inv[None, None, :] - 1 / np.where(inside, truth, 1 / inv[0])[..., None]),
                     axis=2)
    true = np.where(inside, true, sweep)
    bands = (true[S // 2, S // 4], true[S // 2, 3 * S // 4])
    for name, lab in (("the sweep's labels", sweep), ("the true labels", true),
                      ("band 1's plane everywhere", np.full((S, S), bands[0])),
                      ("band 2's plane everywhere", np.full((S, S), bands[1]))):
        print(f"{name}: within one spacing {within(lab):.3f}, score {score(lab)[1]:.4f}")
    t0 = time.time()
    if start == "sweep":
        lab, block, moves = sweep.copy(), S // 8, lambda c: [c - 2, c - 1, c + 1, c + 2]
    else:
        best = min((score(np.full((S, S), j), its=25)[1], j) for j in range(STEPS))
        lab, block, moves = np.full((S, S), best[1]), S // 4, lambda c: range(STEPS)
        print(f"best single plane {best[1]}: within one spacing {within(lab):.3f}")
    x, e = score(lab)
    for sweep_pass in range(2):
        for bi in range(0, S, block):
            for bj in range(0, S, block):
                cur = np.bincount(lab[bi:bi + block, bj:bj + block].ravel()).argmax()
                found = None
                for c in moves(cur):
                    if c < 0 or c >= STEPS or c == cur:
                        continue
                    trial = lab.copy()
                    trial[bi:bi + block, bj:bj + block] = c
                    x2, e2 = score(trial, x, its=15 if start == "sweep" else 10)
                    if e2 < (e if found is None else found[0]):
                        found = (e2, trial, x2)
                if found is not None:
                    e, lab, x = found
        print(f"pass {sweep_pass + 1}: within one spacing {within(lab):.3f}, score {e:.4f}, "
              f"{time.time() - t0:.0f} s")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sweep")
