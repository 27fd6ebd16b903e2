"""calibrate on clipped captures and captures of absurd scale, both faces. The captures are
rendered by tests/python/calib_render.py (numpy alone, no pinmask PSF code) and clipped by
numpy: a float capture has no known ceiling, so a flat top of pixels at exactly its largest
value is taken as one (--saturation auto; saturation_level=None). Most spots clipped: refused,
as an integer file's saturated spots are; a few: a warning naming the count. A capture scaled
by 1e300 is refused naming its scale (the fit ended on "Fisher information is singular")."""
import os
import sys
import warnings

import numpy as np
import pytest

import pinmask

sys.path.insert(0, os.path.dirname(__file__))
import test_calibrate_coverage as coverage  # noqa: E402

BACKGROUND = coverage.BACKGROUND


@pytest.fixture(scope="module")
def rendered():
    """The NIR camera's 340 x 340 crop, one noise seed: (mask, capture, dark frame)."""
    mask, clean, _, _, _ = coverage.make_setup("nir-crop-340")
    import calib_render
    point = calib_render.noisy(clean, 1, background=BACKGROUND)
    return mask, point, np.full(point.shape, BACKGROUND)


def calibrate(point, mask, dark, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = pinmask.calibrate(point, mask, dark=dark, **kw)
    return r, [str(w.message) for w in caught]


@pytest.fixture(scope="module")
def unclipped(rendered):
    mask, point, dark = rendered
    return calibrate(point, mask, dark)


def test_an_unclipped_capture_has_no_plateau(unclipped):
    r, said = unclipped
    assert r["saturated_plateau"] is None and r["saturated_spots"] == 0 and not said
    assert r["chi2_reduced"] < 1.2


def test_clipped_at_half_the_peak_is_refused_like_saturated_counts(rendered, cli, tmp_path):
    mask, point, dark = rendered
    clipped = np.minimum(point, 0.5 * point.max())
    at_max = int((clipped == clipped.max()).sum())
    assert at_max > 1000
    pattern = (r"saturation over most spots: \d+ of \d+ spots .* reach the saturation level "
               r"388\.6.*no saturation_level given.*%d pixels form a flat top.*expose shorter"
               % at_max)
    with pytest.raises(ValueError, match=pattern):
        pinmask.calibrate(clipped, mask, dark=dark)
    # The command line: the same refusal, naming its flag; --saturation none fits as before.
    mask.save(str(tmp_path / "m.mask.json"))
    np.save(tmp_path / "clipped.npy", clipped)
    np.save(tmp_path / "dark.npy", dark)
    msg = cli.error("calibrate", "clipped.npy", "--mask", "m.mask.json", "--dark", "dark.npy",
                    "-o", "cal")
    assert "no --saturation given" in msg and f"{at_max} pixels form a flat top" in msg
    assert not (tmp_path / "cal").exists()


def test_a_few_clipped_spots_warn_with_the_count(rendered, cli, tmp_path):
    mask, point, dark = rendered
    brighter = point.copy()
    brighter[:85] *= 2.0  # the top quarter twice as bright, then clipped at the old peak
    clipped = np.minimum(brighter, point.max())
    at_max = int((clipped == clipped.max()).sum())
    r, said = calibrate(clipped, mask, dark)
    assert r["saturated_plateau"] == {"pixels": at_max, "level": point.max()}
    assert 0 < r["saturated_spots"] < len(r["pinholes"]) / 2
    assert len(said) == 1
    assert (f"{at_max} pixels at exactly its largest value" in said[0] and
            f"{r['saturated_spots']} of" in said[0] and "expose shorter" in said[0] and
            "saturation_level" in said[0])
    mask.save(str(tmp_path / "m.mask.json"))
    np.save(tmp_path / "clipped.npy", clipped)
    np.save(tmp_path / "dark.npy", dark)
    p = cli.run("calibrate", "clipped.npy", "--mask", "m.mask.json", "--dark", "dark.npy",
                "-o", "cal", "--json")
    warning = [l for l in p.stderr.splitlines() if l.startswith("pinmask: warning: ")]
    assert len(warning) == 1
    assert f"{at_max} pixels at exactly" in warning[0] and "--saturation" in warning[0]
    import json
    assert json.loads(p.stdout)["saturated_plateau"] == {"pixels": at_max,
                                                         "level": point.max()}
    # A value given (here none, saturation_level=inf in Python) is the user's word: no
    # detection, no warning.
    p = cli.run("calibrate", "clipped.npy", "--mask", "m.mask.json", "--dark", "dark.npy",
                "-o", "cal2", "--saturation", "none", "--json")
    assert "warning" not in p.stderr and json.loads(p.stdout)["saturated_plateau"] is None


def test_a_symmetric_unclipped_peak_is_no_plateau():
    # Spots centred between pixels: 2 x 2 pixels share the peak exactly (noiseless renders), each
    # with 2 neighbours at it; 20 such spots make 80 pixels at the maximum but no flat top.
    img = np.zeros((100, 100))
    for k in range(20):
        r, c = 10 + 4 * (k // 5) * 4, 10 + 16 * (k % 5)
        img[r:r + 2, c:c + 2] = 5.0
        img[r - 1, c:c + 2] = img[r + 2, c:c + 2] = 2.0
    assert (img == img.max()).sum() == 80
    mask = pinmask.generate(family="random", grid=10, holes=14, spacing=2, tiles=4, seed=5)
    with pytest.raises(ValueError) as e:  # not a capture of the mask: refused, but not as clipped
        pinmask.calibrate(img, mask)
    assert "saturat" not in str(e.value)


@pytest.mark.parametrize("factor", [1e300, 1e60, 1e-12, 1e-300])
def test_a_capture_out_of_scale_is_refused_naming_its_scale(rendered, cli, tmp_path, factor):
    mask, point, dark = rendered
    scaled = point * factor
    with pytest.raises(ValueError, match=r"the capture's scale is out of range: its largest "
                                         r"value is .*between 0\.0001 and 1e\+24"):
        pinmask.calibrate(scaled, mask)
    mask.save(str(tmp_path / "m.mask.json"))
    np.save(tmp_path / "scaled.npy", scaled)
    msg = cli.error("calibrate", "scaled.npy", "--mask", "m.mask.json", "-o", "cal")
    assert "the capture's scale is out of range" in msg


def test_scale_inside_the_range_fits_the_same_geometry(rendered, unclipped):
    mask, point, dark = rendered
    ref, _ = unclipped
    r = pinmask.calibrate(point * 1e18, mask, dark=dark * 1e18)
    assert abs(r["rotation_deg"] - ref["rotation_deg"]) < 1e-3 * ref["rotation_sigma_deg"]
    assert r["chi2_reduced"] == pytest.approx(ref["chi2_reduced"], rel=1e-4)
