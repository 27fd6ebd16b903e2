"""The depth costs compared in docs/depth.md section 3b (depth_costs.py): the identity that ties
the evidence's two forms, and rows of the comparison table held."""
import pathlib
import tempfile

import numpy as np
import pytest
from scipy.ndimage import uniform_filter

import depth_costs as dc
import depth_scenes as ds
import pinmask


def _mask_json(camera):
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=pinmask.Camera(**camera), kernel="box").save(str(path))
        return ds.load(path)


def test_evidence_and_its_split_form_agree_over_the_frame():
    # y^T (K S K^H + s^2)^-1 y = min_x |y - K x|^2 / s^2 + x^H S^-1 x: with a window of the whole
    # (cyclic) frame both forms give the same cost at every pixel, for any PSF and capture.
    rng = np.random.default_rng(4)
    y = rng.random((33, 33))
    psfs = [rng.random((33, 33)) ** 4 for _ in range(3)]
    a = dc.costs(y, psfs, "evidence", window=33)
    b = dc.costs(y, psfs, "split", window=33)
    assert np.allclose(a, b, rtol=1e-9, atol=0)
    assert not np.allclose(a[0], a[1], rtol=1e-6)  # the planes differ
    # And the local form is the box mean of a per-pixel energy: with window 1 it is that energy.
    c = dc.costs(y, psfs, "evidence", window=1)
    assert np.allclose(uniform_filter(c[0], 33, mode="wrap"), a[0], rtol=1e-9)


# camera, scene (a SCENE_KINDS name or one plane's range position) -> the fraction of the
# scene's pixels within one plane spacing for residual, evidence, split, joint (384 x 384,
# window 121, 16 planes; docs/depth.md section 3b).
ROWS = {
    ("phone", "two planes"): (0.49, 0.00, 0.00, 0.07),
    ("paper", 0.5): (0.22, 0.96, 0.92, 0.03),
}


@pytest.mark.parametrize("camera,scene", list(ROWS))
def test_comparison_row(camera, scene):
    cam, near, far = ds.CAMERAS[camera]
    mj = _mask_json(cam)
    inv = ds.range_inverse(near, far, np.linspace(0, 1, 16))
    spacing = abs(inv[1] - inv[0])
    psfs = [ds.exact_psf(mj, 1 / v, 384, 384) for v in inv]
    positions = [scene] if isinstance(scene, float) else ds.SCENE_KINDS[scene]
    cap, truth, _, inside, _ = ds.kind_scene(mj, positions, near, far, 384, 2000.0, 1)
    for kind, held in zip(("residual", "evidence", "split", "joint"), ROWS[(camera, scene)]):
        label = dc.costs(cap, psfs, kind).argmin(0)
        within = np.mean(abs(inv[label][inside] - 1 / truth[inside]) <= spacing)
        assert within == pytest.approx(held, abs=0.03), kind


def test_real_tilted_target():
    # docs/depth.md section 3b: on the measured stack the evidence's frame-mean minimum is plane
    # 17 (the README's independent check: planes 16-20 decode the bars sharpest), the residual's
    # plane 36; neither per-pixel map follows the tilt (|Spearman| < 0.5 along rows and columns).
    import depth_real as dr
    if not (dr.folder() / "example_raw.png").exists():
        pytest.skip(f"real data not found at {dr.folder()}")
    raw, psfs = dr.load(dr.folder())
    held = {"residual": (36, 0.37, -0.30), "evidence": (17, 0.16, -0.20),
            "split": (17, 0.46, 0.14)}
    for kind, (plane, by_col, by_row) in held.items():
        got = dr.figures(raw, psfs, kind)
        assert got[0] == plane, kind
        assert got[1:] == pytest.approx((by_col, by_row), abs=0.01), kind
    capture, median, by_col, by_row, evidence = dr.depthmap_figures(raw, psfs)
    assert (capture, median, by_col, by_row) == pytest.approx((35.96, 41.91, 0.30, -0.34),
                                                              abs=0.01)
    # pinmask's own whole-capture estimate by the evidence: measured 17.26, within the README's
    # planes 16-20.
    assert evidence == pytest.approx(17.26, abs=0.01)


def test_library_evidence_matches_numpy():
    # pinmask's per-plane evidence (decode/depthmap/sweep_cost, over the half spectrum) against the
    # formula written here over the full spectrum: mean_f [P / D + log D], D = |H|^2 A /
    # (lambda + eps) + s^2, s^2 the mean of P where lambda > 6, A = (sum P - s^2 N) / sum
    # |H|^2 / (lambda + eps); odd and even sides, chosen with no lambda within 1e-3 of 6 (where
    # the two paths' rounding of lambda could disagree on the noise band).
    rng = np.random.default_rng(5)
    for rows, cols in ((45, 50), (44, 51)):
        assert np.min(abs(dc.laplacian_eigen(rows, cols) - 6.0)) > 1e-3
        # Values exact in float32, so that any conversion on the way keeps them.
        cap = (rng.random((rows, cols)) + 0.2).astype(np.float32).astype(float)
        psfs = [((rng.random((rows, cols)) > 0.97) * rng.random((rows, cols)))
                .astype(np.float32).astype(float) for _ in range(3)]
        r = pinmask.depthmap(cap, psf_stack=[(1.0 + k, p) for k, p in enumerate(psfs)],
                             window=15)
        lam = dc.laplacian_eigen(rows, cols)
        power = abs(np.fft.fft2(cap)) ** 2 / cap.size
        s2 = power[lam > 6].mean()
        for plane, psf in zip(r["planes"], psfs):
            h2 = abs(np.fft.fft2(psf / psf.sum())) ** 2
            a = (power.sum() - s2 * cap.size) / np.sum(h2 / (lam + dc.EPS))
            d = h2 * a / (lam + dc.EPS) + s2
            assert plane["evidence"] == pytest.approx(np.mean(power / d + np.log(d)), rel=1e-9)
        best = int(np.argmin([p["evidence"] for p in r["planes"]]))
        assert 1.0 / r["capture_evidence_depth_m"] == pytest.approx(1.0 / (1.0 + best), abs=0.5)
