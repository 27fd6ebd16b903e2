"""The camera's band (Camera.bandwidth_m, `--bandwidth`): the PSF of a camera with a band against
a weighted sum of monochromatic PSFs summed here in numpy, the camera file, and optics() against
`pinmask design --json`."""
import json
import math

import numpy as np
import pytest

import pinmask

FIELDS = ["object_distance_m", "lens_focal_m", "sensor_distance_m", "wavelength_m",
          "pixel_pitch_m", "pinhole_m", "sensor_cols", "sensor_rows", "bandwidth_m"]


def with_fields(c, **changes):
    values = {k: getattr(c, k) for k in FIELDS}
    values.update(changes)
    return pinmask.Camera(**values)


def half_max_samples(lam, fwhm):
    # A Gaussian is half its peak at +-FWHM/2, so 2^(-k^2/4) of it at k FWHM/4 (k = -6..6).
    k = np.arange(-6, 7)
    w = 2.0 ** (-(k * k).astype(float) / 4)
    return lam + k * fwhm / 4, w / w.sum()


# Two cameras that are not the paper's: a machine-vision camera at 2 m under a 530 nm LED, and a
# lensless camera under a broad 650 nm source.
CAMERAS = [
    pinmask.Camera(pixel_pitch_m="3.45um", sensor_cols=2448, sensor_rows=2048,
                   lens_focal_m="25mm", sensor_distance_m="20mm", object_distance_m="2m",
                   wavelength_m="530nm", pinhole_m="120um", bandwidth_m="25nm"),
    pinmask.Camera(lens_focal_m="inf", sensor_distance_m="30mm", object_distance_m="3m",
                   wavelength_m="650nm", pinhole_m="200um", pixel_pitch_m="20um",
                   bandwidth_m="80nm"),
]


@pytest.mark.parametrize("camera", CAMERAS)
@pytest.mark.parametrize("geometry", ["integer", "exact"])
def test_psf_with_band_is_weighted_sum_of_monochromatic(camera, geometry):
    mask = pinmask.generate(grid=8, holes=6, tiles=1, seed=5, camera=camera, kernel="fresnel")
    kw = dict(geometry=geometry)
    if geometry == "exact":
        kw["size"] = (96, 96)
    got = pinmask.psf(mask, **kw)
    lams, weights = half_max_samples(camera.wavelength_m, camera.bandwidth_m)
    want = np.zeros_like(got)
    for lam, w in zip(lams, weights):
        mask.camera = with_fields(camera, wavelength_m=float(lam), bandwidth_m=0.0)
        want += w * pinmask.psf(mask, **kw)
    assert np.abs(got - want).max() <= 1e-12 * want.max()
    mask.camera = with_fields(camera, bandwidth_m=0.0)
    assert np.abs(got - pinmask.psf(mask, **kw)).max() > 1e-4 * want.max()  # the band matters


def test_camera_bandwidth_field_file_and_refusals(tmp_path):
    c = pinmask.Camera(wavelength_m="850nm", bandwidth_m="30nm")
    assert c.bandwidth_m == pytest.approx(30e-9)
    assert "bandwidth_m=" + repr(c.bandwidth_m) + ")" in repr(c)
    assert c != pinmask.Camera(wavelength_m="850nm")
    pinmask.save_camera(c, tmp_path / "c.camera.json")
    back = pinmask.load_camera(tmp_path / "c.camera.json")
    assert back == c and back.bandwidth_m == c.bandwidth_m
    assert pinmask.Camera().bandwidth_m == 0.0
    assert "bandwidth" not in pinmask.Camera().to_json()
    for bad in (-1e-9, float("nan"), 1e-6, "2um"):
        with pytest.raises(ValueError, match="bandwidth_m"):
            pinmask.Camera(bandwidth_m=bad)


def test_optics_band_and_kernel_equal_cli_design_json(cli):
    flags = ["--pixel-pitch", "5.86um", "--sensor", "1920x1200", "--lens-focal", "75mm",
             "--sensor-distance", "45mm", "--object-distance", "1.2m", "--wavelength", "850nm",
             "--pinhole", "455.406um", "--bandwidth", "30nm"]
    j = json.loads(cli.run("design", *flags, "--json").stdout)
    d = pinmask.optics(pinmask.Camera(
        pixel_pitch_m="5.86um", sensor_cols=1920, sensor_rows=1200, lens_focal_m="75mm",
        sensor_distance_m="45mm", object_distance_m="1.2m", wavelength_m="850nm",
        pinhole_m="455.406um", bandwidth_m="30nm"))
    assert d["spectrum"]["bandwidth_m"] == j["spectrum"]["bandwidth_m"]
    assert [list(s) for s in d["spectrum"]["wavelengths"]] == j["spectrum"]["wavelengths"]
    assert d["kernel"]["enclosed_energy"] == j["kernel"]["enclosed_energy"]
    assert list(d["kernel"]["support_px"]) == j["kernel"]["support_px"]
    assert d["kernel_model"] == j["kernel_model"]
    assert len(d["kernel_warnings"]) == len(j["kernel_warnings"])
    lams, weights = half_max_samples(850e-9, 30e-9)
    got = np.array(d["spectrum"]["wavelengths"])
    assert np.allclose(got[:, 0], lams, rtol=1e-15) and np.allclose(got[:, 1], weights, rtol=1e-13)
    assert math.isclose(sum(got[:, 1]), 1.0, rel_tol=1e-15)
