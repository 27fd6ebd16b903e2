"""The four-camera table of docs/depth.md (section 3a, scripts/depthmap_cameras.py): each row's
figures held, on scenes rendered by the independent numpy model of depth_scenes.py (box spots,
the masks' kernel the box too, so the sweep's model is the scene's and what is measured is the
method). Also the renderer's own checks against closed forms."""
import math

import numpy as np
import pytest

import pinmask
from depth_scenes import (CAMERAS, SCENE_KINDS, exact_psf, kind_scene, measure_kind,
                          range_inverse)

SIZES = {kind: 384 for kind in SCENE_KINDS}


def _mask(tmp_path, camera):
    path = tmp_path / "m.mask.json"
    pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                     camera=pinmask.Camera(**camera), kernel="box").save(str(path))
    return path


@pytest.mark.parametrize("name", list(CAMERAS))
def test_renderer_psf_scales_with_the_magnification(tmp_path, name):
    # Closed form: the spots sit at M(u) s / w, so the PSF's second moment about the frame's
    # centre is M(u)^2 / w^2 times the mean s^2 over the tiled mask's cells, plus a box's own
    # variance side^2 / 12 per axis; each tile's pinholes hold unit light.
    import json
    cam, near, far = CAMERAS[name]
    mj = json.loads(_mask(tmp_path, cam).read_text())
    n, (tr, tc) = mj["pattern"]["n"], mj["pattern"]["tiles"]
    d, w = cam["pinhole_m"], cam["pixel_pitch_m"]
    for u in (near, far):
        mag = 1 - cam["sensor_distance_m"] / cam["lens_focal_m"] + cam["sensor_distance_m"] / u
        psf = exact_psf(mj, u, 512, 512)
        assert psf.sum() == pytest.approx(tr * tc, rel=1e-12)
        yy, xx = np.mgrid[0:512, 0:512] + 0.5 - 256.0
        s2 = np.mean([((a * n + r + 0.5 - tr * n / 2) ** 2 + (b * n + c + 0.5 - tc * n / 2) ** 2)
                      for a in range(tr) for b in range(tc) for r, c in mj["pattern"]["pinholes"]])
        side = d * abs(mag) / w
        expected = s2 * (d * mag / w) ** 2 + 2 * side * side / 12
        moment = float(np.sum(psf * (yy ** 2 + xx ** 2))) / (tr * tc)
        # Within 1 px^2 (the moment is taken at the pixels' centres, the boxes are integrated
        # over the pixels); one pixel of pattern change moves it by about 2 s_max pixels^2.
        assert moment == pytest.approx(expected, abs=1.0)


def test_renderer_scene_layout(tmp_path):
    cam, near, far = CAMERAS["phone"]
    mj = __import__("json").loads(_mask(tmp_path, cam).read_text())
    cap, truth, tex, inside, flat = kind_scene(mj, [0.25, 0.75], near, far, 384, 1e9, 2,
                                               flat_right=True)
    u = 1 / range_inverse(near, far, [0.25, 0.75])
    assert np.all(np.isnan(truth[~inside]))
    assert np.all(truth[48:336, 48:192] == u[0]) and np.all(truth[48:336, 192:336] == u[1])
    assert np.all(flat == (inside & (truth == u[1]))) and np.all(tex[flat] == 0.5)
    # Light is conserved by the blur (2 x 2 tiles: 4 units of light per unit of scene; the
    # PSF, about 290 px across, fits the frame), to the photon noise of 1e9 per unit.
    assert cap.sum() == pytest.approx(4 * tex.sum(), rel=1e-6)
