"""Camera lengths that cannot silently be absurd, and a camera given without its pinhole: the
module against the command line, and against closed forms written out here."""
import json
import math
import warnings

import pytest

import pinmask

# A machine-vision camera without a pinhole (test_design.py's MV, pinhole left out).
MV_FLAGS = ["--pixel-pitch", "3.45um", "--sensor", "2448x2048", "--lens-focal", "25mm",
            "--sensor-distance", "20mm", "--object-distance", "2m", "--wavelength", "530nm"]
MV = dict(pixel_pitch_m="3.45um", sensor_cols=2448, sensor_rows=2048, lens_focal_m="25mm",
          sensor_distance_m="20mm", object_distance_m="2m", wavelength_m="530nm")


@pytest.mark.parametrize("kwargs,meant", [
    (dict(pinhole_m=300), "300um"),
    (dict(pixel_pitch_m=30), "30um"),
    (dict(wavelength_m=550), "550nm"),
    (dict(sensor_distance_m=55), "55mm"),
    (dict(pinhole_m="0.44"), "0.44mm"),
])
def test_a_length_without_its_unit_is_refused_with_the_unit_meant(cli, kwargs, meant):
    (keyword, value), = kwargs.items()
    with pytest.raises(ValueError, match="^%s = .*did you mean %s\\?" % (keyword, meant)):
        pinmask.Camera(**kwargs)
    flag = {"pinhole_m": "--pinhole", "pixel_pitch_m": "--pixel-pitch",
            "wavelength_m": "--wavelength", "sensor_distance_m": "--sensor-distance"}[keyword]
    r = cli.run("design", flag, str(value), expect=2)
    assert "did you mean %s?" % meant in r.stderr


def test_a_camera_without_a_pinhole_gets_the_whole_pixel_optimum(cli):
    with pytest.warns(UserWarning, match="no pinhole_m given: using d = "):
        cam = pinmask.Camera(**MV)
    f, fl, u, lam, w = 20e-3, 25e-3, 2.0, 530e-9, 3.45e-6
    z = 1 / (1 / f - 1 / fl + 1 / u)
    m = 1 - f / fl + f / u
    n = round(1.56 * math.sqrt(lam * z) * m / w)
    assert abs(cam.pinhole_m - n * w / m) <= 0.5e-9 + 1e-15
    # The command line chooses the same pinhole.
    j = json.loads(cli.run("design", *MV_FLAGS, "--json").stdout)
    assert j["camera"]["pinhole_m"] == cam.pinhole_m
    # Given, or the paper's camera: no choice, no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert pinmask.Camera(**MV, pinhole_m="345um").pinhole_m == pytest.approx(345e-6)
        assert pinmask.Camera().pinhole_m == 440e-6
        assert pinmask.Camera(object_distance_m=2.0).pinhole_m == 440e-6


def test_a_solve_far_from_the_optimum_says_where_it_is(cli):
    cam = pinmask.Camera(lens_focal_m="inf", sensor_distance_m="5mm", pinhole_m="440um")
    with pytest.warns(UserWarning, match="5.38x the diffraction optimum"):
        pinmask.optics(cam, solve="pinhole")
    r = cli.run("design", "--preset", "paper", "--lens-focal", "inf", "--sensor-distance", "5mm",
                "--solve", "pinhole", "--json")
    assert "5.38x the diffraction optimum" in r.stderr


def test_optics_has_the_image_distance_and_the_first_zero(cli):
    d = pinmask.optics()
    assert d["image_distance_at_u_m"] == pytest.approx(1 / (1 / 0.12 - 1 / 6.0), rel=1e-12)
    assert d["diffraction_first_zero_px"] == pytest.approx(550e-9 * 55e-3 / (440e-6 * 30e-6),
                                                           rel=1e-12)
    j = json.loads(cli.run("design", "--preset", "paper", "--json").stdout)
    assert d["image_distance_at_u_m"] == j["image_distance_at_u_m"]
    assert d["diffraction_first_zero_px"] == j["diffraction_first_zero_px"]
