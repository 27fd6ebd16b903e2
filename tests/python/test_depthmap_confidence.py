"""The depth map's confidence as a probability (decode/depthmap/calibrated_confidence, docs/depth.md
section 3c), on scenes of cameras its map was not fitted on (the fit used the machine-vision and
visible 35 mm cameras, scene seed 1; these are the paper and phone cameras, seed 2), rendered by
the independent numpy model of depth_scenes.py: among the pixels at confidence >= c, their share
and the share within one plane spacing, as measured (scripts/depthmap_reliability.py pools these
with the other scenes into the section's diagram)."""
import pathlib
import sys

import numpy as np
import pytest

import pinmask

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import depth_scenes as ds  # noqa: E402

# camera, scene -> (c, share at confidence >= c, within one spacing there) for c = 0.2, 0.5, 0.9.
HELD = {
    ("phone", "two planes"): ((0.2, 1.0, 0.404), (0.5, 0.711, 0.523), (0.9, 0.235, 0.462)),
    ("paper", 0.5): ((0.2, 1.0, 0.544), (0.5, 0.0, None), (0.9, 0.0, None)),
}


@pytest.mark.parametrize("camera,kind", list(HELD))
def test_confidence_on_cameras_outside_its_fit(tmp_path, camera, kind):
    cam, near, far = ds.CAMERAS[camera]
    path = tmp_path / "m.mask.json"
    pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                     camera=pinmask.Camera(**cam), kernel="box").save(str(path))
    positions = [kind] if isinstance(kind, float) else ds.SCENE_KINDS[kind]
    cap, truth, _, inside, _ = ds.kind_scene(ds.load(path), positions, near, far, 384, 2000.0, 2)
    r = pinmask.depthmap(cap, str(path), from_m=near, to_m=far, steps=16)
    spacing = (1 / near - 1 / far) / 15
    hit = (abs(1 / r["depth_m"] - 1 / truth) <= spacing)[inside]
    conf = r["confidence"][inside]
    # The confidence is the knots' map of the cost margin.
    assert np.all((conf >= 0.2) & (conf <= 0.95))
    for c, share, within in HELD[(camera, kind)]:
        sure = conf >= c
        assert sure.mean() == pytest.approx(share, abs=0.01)
        if within is not None:
            assert hit[sure].mean() == pytest.approx(within, abs=0.01)
