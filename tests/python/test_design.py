"""Optics numbers and the camera: the module against `pinmask design --json`."""
import json
import math

import pytest

import pinmask


def test_optics_equals_cli_design_json(cli):
    j = json.loads(cli.run("design", "--preset", "paper", "--json").stdout)
    d = pinmask.optics()
    # Every number design --json prints, the working distance included (test_parity.py checks
    # the other keys and other cameras).
    keys = [k for k, v in j.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    assert len(keys) > 25 and all(k in d for k in keys), [k for k in keys if k not in d]
    for k in keys:
        assert d[k] == j[k], k  # the same library call: identical doubles
    assert d["kernel_model"] == j["kernel_model"]
    assert d["lsi_shift_invariant"] == j["lsi_shift_invariant"]
    assert d["periods_on_sensor"] == j["periods_on_sensor"]


def test_optics_paper_figures():
    d = pinmask.optics(pinmask.paper_camera())
    # DESIGN.md section 1: 7.94 pixels per cell, N_F 1.6 without the lens, z_eff 101.5 mm.
    assert d["pixels_per_cell_at_inf"] == pytest.approx(7.944, abs=1e-3)
    assert d["fresnel_number"] == pytest.approx(1.6, abs=0.01)
    assert d["effective_distance_at_inf_m"] == pytest.approx(0.1015, abs=1e-4)


def test_camera_units_and_infinity():
    c = pinmask.Camera(pinhole_m="440um", sensor_distance_m="55mm", object_distance_m="inf")
    assert c.pinhole_m == pytest.approx(440e-6)
    assert c.sensor_distance_m == pytest.approx(0.055)
    assert math.isinf(c.object_distance_m)
    d = pinmask.optics(c)
    assert d["lsi_mismatch_at_inf_px"] == 0.0  # u = inf: no object term


def test_camera_invalid_is_value_error():
    with pytest.raises(ValueError, match="pinhole_m"):
        pinmask.Camera(pinhole_m=-1e-6)
    with pytest.raises(ValueError, match="unit|pinhole"):
        pinmask.Camera(pinhole_m="12 parsecs")


def test_choose_kernel_model():
    model, reason = pinmask.choose_kernel_model(0.87)
    assert model == "fresnel" and reason
    assert pinmask.choose_kernel_model(1e-3)[0] == "fraunhofer"
    assert pinmask.choose_kernel_model(1e5)[0] == "box"
