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
    # docs/design.md section 2: 7.94 pixels per cell, N_F 1.6 without the lens, z_eff 101.5 mm.
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


# Solving the pinhole (design --pixels-per-cell / --solve pinhole): a machine-vision camera,
# not the paper's (the example of `pinmask design --help`).
MV_FLAGS = ["--pixel-pitch", "3.45um", "--sensor", "2448x2048", "--lens-focal", "25mm",
            "--sensor-distance", "20mm", "--object-distance", "2m", "--wavelength", "530nm"]
MV = dict(pixel_pitch_m="3.45um", sensor_cols=2448, sensor_rows=2048, lens_focal_m="25mm",
          sensor_distance_m="20mm", object_distance_m="2m", wavelength_m="530nm")


def same_report(d, j):
    keys = [k for k, v in j.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    assert len(keys) > 25
    for k in keys:
        assert d[k] == j[k], k


@pytest.mark.parametrize("cli_args,kwargs", [
    (["--pixels-per-cell", "21"], dict(pixels_per_cell=21)),
    (["--solve", "pinhole", "--fab-grid", "1um"], dict(solve="pinhole", fab_grid="1um")),
    (["--pixels-per-cell", "12", "--vendor", "film-plotter"],
     dict(pixels_per_cell=12, vendor="film-plotter")),
])
def test_optics_solving_the_pinhole_equals_cli(cli, tmp_path, cli_args, kwargs):
    j = json.loads(cli.run("design", *MV_FLAGS, *cli_args, "--save-camera", "cli.camera.json",
                           "--json").stdout)
    d = pinmask.optics(pinmask.Camera(**MV), **kwargs,
                       save_camera=str(tmp_path / "py.camera.json"))
    same_report(d, j)
    assert "pinhole_on_grid_m" in j and d["pinhole_on_grid_m"] == j["pinhole_on_grid_m"]
    # The solved camera is the one --save-camera writes, and the report's camera.
    assert (tmp_path / "py.camera.json").read_bytes() == \
        (tmp_path / "cli.camera.json").read_bytes()
    assert d.camera == j["camera"]
    assert pinmask.load_camera(str(tmp_path / "py.camera.json")).pinhole_m == d.camera.pinhole_m
    # Independent of pinmask: N = d M(u) / w with M(u) = 1 - f/f' + f/u, before the grid.
    f, fl, u, w = 0.020, 0.025, 2.0, 3.45e-6
    n_whole = round(d["pinhole_solved_m"] * (1 - f / fl + f / u) / w)
    assert abs(d["pinhole_solved_m"] * abs(1 - f / fl + f / u) / w - n_whole) < 1e-9
    if "pixels_per_cell" in kwargs:
        assert n_whole == kwargs["pixels_per_cell"]


@pytest.mark.parametrize("kwargs,pattern", [
    (dict(solve="lens"), "^solve = lens: must be 'pinhole'"),
    (dict(fab_grid="1um"), "^fab_grid = 1um: sets the grid a solved pinhole lands on"),
    (dict(pixels_per_cell=12, fab_grid="1um", vendor="film-plotter"), "^fab_grid = 1um: and vendor"),
    (dict(pixels_per_cell=0), "^pixels_per_cell = 0"),
    (dict(save_camera="/nonexistent/x.camera.json"), "^save_camera = .*folder does not exist"),
])
def test_optics_solving_errors_name_keywords(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        pinmask.optics(pinmask.Camera(**MV), **kwargs)


@pytest.mark.parametrize("grid, holes, spacing", [(8, 40, 2.0), (16, 20, 3.0), (5, 3, 6.0)])
def test_optics_spacing_bound_equals_cli(cli, grid, holes, spacing):
    p = cli.run("design", "--grid", grid, "--holes", holes, "--spacing", spacing, "--json")
    j = json.loads(p.stdout)
    d = pinmask.optics(grid=grid, holes=holes, spacing=spacing)
    for k in ("spacing_cells", "max_holes_at_spacing", "max_holes_reason"):
        assert d[k] == j[k], k
    # A pinhole closer than the spacing to its own periodic copy: nothing fits.
    if spacing > grid:
        assert d["max_holes_at_spacing"] == 0
    # Two pinholes at least `spacing` apart on the torus: the bound can never be below what a
    # placement on a lattice of step ceil(spacing) realises.
    step = math.ceil(spacing)
    assert d["max_holes_at_spacing"] >= (grid // step) ** 2 if step <= grid else True
    fits = holes <= d["max_holes_at_spacing"]
    assert ("do not fit" in p.stderr) == (not fits)


def test_optics_spacing_refused():
    with pytest.raises(ValueError, match="spacing"):
        pinmask.optics(spacing=-1)
