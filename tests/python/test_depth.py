"""pinmask.depth() against `pinmask depth --json` on the same inputs (two cameras, the photon
model and a Gaussian level), and its refusals named by keyword."""
import json
import math

import pytest

import pinmask


def _cli_depth(cli, mask_path, *args):
    return json.loads(cli.run("depth", mask_path, "--json", *args).stdout)


def _same(py_records, cli_records):
    assert len(py_records) == len(cli_records)
    for p, c in zip(py_records, cli_records):
        assert set(p) == set(c)  # the same keys as depth --json
        for key, value in c.items():
            if value is None:
                assert p[key] is None, key
            else:
                # The same library call: equal up to the JSON's 17 significant digits.
                assert p[key] == pytest.approx(value, rel=1e-12, abs=1e-12), key


def test_depth_photon_model_matches_the_command_line(cli, mask7, tmp_path):
    path = tmp_path / "m.mask.json"
    mask7.save(str(path))
    py = pinmask.depth(str(path), distances=[3.0, 6.0], photons=20, read_noise=6, tv=False)
    _same(py, _cli_depth(cli, path, "--distances", "3m,6m", "--photons", "20",
                         "--read-noise", "6", "--no-tv"))
    assert py[0]["wiener_nsr"] != 0.01  # tuned


def test_depth_other_camera_range_and_fixed_nsr(cli, tmp_path):
    # A machine-vision camera at 2 m: 3.45 um pixels, 25 mm lens, sensor 20 mm behind it.
    camera = pinmask.Camera(object_distance_m=2.0, lens_focal_m=0.025, sensor_distance_m=0.020,
                            wavelength_m=530e-9, pixel_pitch_m=3.45e-6, pinhole_m=115e-6,
                            sensor_cols=512, sensor_rows=512)
    mask = pinmask.generate(family="random", grid=16, holes=12, spacing=2, tiles=2, seed=3,
                            camera=camera)
    path = tmp_path / "mv.mask.json"
    mask.save(str(path))
    py = pinmask.depth(mask, from_m=1.0, to_m=math.inf, steps=3, snr_db=25, nsr="0.02",
                       scenes=["letter-R"], seed=4)
    _same(py, _cli_depth(cli, path, "--from", "1m", "--to", "inf", "--steps", "3", "--snr",
                         "25", "--nsr", "0.02", "--scenes", "letter-R", "--seed", "4"))
    assert py[-1]["object_distance_m"] is None  # inf, as the JSON's null
    assert all(r["wiener_nsr"] == 0.02 for r in py)


def test_depth_refusals_name_the_keyword(mask7):
    with pytest.raises(ValueError, match="read_noise"):
        pinmask.depth(mask7, distances=[6.0], read_noise=6)
    with pytest.raises(ValueError, match="one level"):
        pinmask.depth(mask7, distances=[6.0], photons=[20, 40])
    with pytest.raises(ValueError, match="nsr"):
        pinmask.depth(mask7, distances=[6.0], nsr="0")
    with pytest.raises(ValueError, match="from_m"):
        pinmask.depth(mask7, distances=[6.0], from_m=1.0, to_m=2.0)
