"""`pinmask depthmap` on scenes rendered by an independent numpy model (depth_scenes.py: each
plane's PSF drawn from the pinhole cells and Eq. (3), photon noise), for two cameras: the
machine-vision camera at close range (u = 0.4-2 m, 20-100 f) and the paper's camera (1-10 m).
The rows hold the figures of docs/depth.md's table (measured with scripts/depthmap_table.py)."""
import json
import math
import pathlib
import sys

import numpy as np
import pytest

import pinmask

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import depth_scenes as ds  # noqa: E402

MV = ds.MACHINE_VISION


def _mask(tmp_path, camera):
    m = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=camera)
    path = tmp_path / "m.mask.json"
    m.save(str(path))
    return path


def _runner(cli, tmp_path, mask_path):
    def run(capture, frm, to, steps):
        cap = tmp_path / "cap.npy"
        np.save(cap, capture.astype(np.float32))
        out = tmp_path / "out"
        p = cli.run("depthmap", cap, "--mask", mask_path, "--from", f"{frm}m", "--to",
                    "inf" if math.isinf(to) else f"{to}m", "--steps", steps, "-o", out, "--json")
        return out, json.loads(p.stdout)
    return run


def _read(path):
    return np.asarray(pinmask.read_image(str(path))[0]).squeeze()


@pytest.mark.parametrize("camera,frm,to,truth,bound", [
    ("mv", 0.4, 2.0, 0.45, 2.0), ("mv", 0.4, 2.0, 1.5, 1.0),
    ("paper", 1.0, 10.0, 2.0, 1.5), ("paper", 1.0, 10.0, 5.0, 1.5)])
def test_whole_capture_depth_of_one_plane(cli, tmp_path, camera, frm, to, truth, bound):
    cam = pinmask.Camera(**MV) if camera == "mv" else pinmask.paper_camera()
    mask = _mask(tmp_path, cam)
    row = ds.measure(_runner(cli, tmp_path, mask), _read, mask, [truth], frm, to, 16, 384,
                     2000.0, 1, baseline=False)
    # Measured 1.70 / 0.54 / 0.88 / 0.60 plane spacings (docs/depth.md).
    assert row["capture_error_planes"] <= bound


def test_three_planes_close_range_row(cli, tmp_path):
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    row = ds.measure(_runner(cli, tmp_path, mask), _read, mask, [0.45, 0.7, 1.5], 0.4, 2.0, 16,
                     384, 2000.0, 1)
    # docs/depth.md: RMS 2.74 plane spacings, 25 % within one spacing (chance: about 19 %);
    # all-in-focus 16.87 dB against 17.20 dB for the best single-plane decode.
    assert row["rms_planes"] <= 3.0
    assert row["within_spacing"] >= 0.2
    assert row["aif_psnr_db"] >= row["single_best_psnr_db"] - 0.6


def test_three_planes_paper_camera_row(cli, tmp_path):
    mask = _mask(tmp_path, pinmask.paper_camera())
    row = ds.measure(_runner(cli, tmp_path, mask), _read, mask, [1.5, 3.0, 8.0], 1.0, 10.0, 16,
                     384, 2000.0, 1)
    # docs/depth.md: RMS 3.09 plane spacings, 30 % within one spacing; all-in-focus 17.97 dB
    # against 17.91 dB.
    assert row["rms_planes"] <= 3.5
    assert row["within_spacing"] >= 0.25
    assert row["aif_psnr_db"] >= row["single_best_psnr_db"] - 0.3


def test_outputs_and_refusals(cli, tmp_path):
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    cap = tmp_path / "c.npy"
    np.save(cap, np.random.default_rng(0).random((64, 64)).astype(np.float32))
    out = tmp_path / "o"
    s = json.loads(cli.run("depthmap", cap, "--mask", mask, "--from", "0.4m", "--to", "2m",
                           "--steps", 4, "--window", 15, "-o", out, "--json").stdout)
    assert s["planes_done"] == 4 and not s["interrupted"]
    assert sum(p["pixel_fraction"] for p in s["planes"]) == pytest.approx(1.0)
    for name in s["files"]:
        assert (out / name).exists(), name
    d = _read(out / "depth.tif")
    assert d.shape == (64, 64) and np.all((d >= 0.4 - 1e-6) & (d <= 2.0 + 1e-6))
    assert "--window" in cli.error("depthmap", cap, "--mask", mask, "--from", "0.4m", "--to",
                                   "2m", "--window", 16, "-o", tmp_path / "x")
    assert "--to" in cli.error("depthmap", cap, "--mask", mask, "--from", "2m", "--to", "1m",
                               "--window", 15, "-o", tmp_path / "x")
    assert "--steps" in cli.error("depthmap", cap, "--mask", mask, "--from", "1m", "--to", "2m",
                                  "--steps", 1, "--window", 15, "-o", tmp_path / "x")
    assert not (tmp_path / "x").exists()
    # An output that would replace the capture: refused before any work, the capture intact.
    inside = tmp_path / "o" / "depth.tif"
    before = inside.read_bytes()
    assert "-o" in cli.error("depthmap", inside, "--mask", mask, "--from", "0.4m", "--to", "2m",
                             "--window", 15, "-o", tmp_path / "o")
    assert inside.read_bytes() == before


def test_python_matches_the_command_line(cli, tmp_path):
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    capture, _, _, _ = ds.scene(ds.load(mask), [0.5, 1.2], 96, 96, 2000.0, 2)
    cap = tmp_path / "c.npy"
    np.save(cap, capture.astype(np.float32))
    out = tmp_path / "o"
    c = json.loads(cli.run("depthmap", cap, "--mask", mask, "--from", "0.4m", "--to", "inf",
                           "--steps", 5, "--window", 31, "-o", out, "--json").stdout)
    p = pinmask.depthmap(str(cap), str(mask), from_m=0.4, to_m=math.inf, steps=5, window=31)
    arrays = {"depth_m", "confidence", "all_in_focus", "label"}
    assert set(p) - arrays == set(c)
    for key, value in c.items():
        if key == "files":
            assert p[key] == []  # nothing written
        elif key in ("planes",):
            assert p[key] == [pytest.approx(x) for x in value]
        elif isinstance(value, float):
            assert p[key] == pytest.approx(value, rel=1e-12), key
        else:
            assert p[key] == value, key
    assert np.array_equal(p["depth_m"].astype(np.float32), _read(out / "depth.tif"))
    assert p["planes"][-1]["object_distance_m"] is None  # inf
    # The array form gives the same maps as the path form.
    q = pinmask.depthmap(np.load(cap), pinmask.load_mask(str(mask)), from_m=0.4, to_m=math.inf,
                         steps=5, window=31)
    assert np.array_equal(q["depth_m"], p["depth_m"]) and q["capture"] is None


def test_python_refusals_name_the_keyword(tmp_path):
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    cap = np.ones((40, 40))
    with pytest.raises(ValueError, match="window"):
        pinmask.depthmap(cap, mask, from_m=0.4, to_m=2.0, window=41)
    with pytest.raises(ValueError, match="window"):
        pinmask.depthmap(cap, mask, from_m=0.4, to_m=2.0, window=8)
    with pytest.raises(ValueError, match="to_m"):
        pinmask.depthmap(cap, mask, from_m=2.0, to_m=1.0, window=15)
    with pytest.raises(ValueError, match="nsr"):
        pinmask.depthmap(cap, mask, from_m=0.4, to_m=2.0, window=15, nsr=0)


@pytest.mark.parametrize("camera,u", [
    (MV, 0.5),  # 115 um pinholes: 8.000 px per cell at 0.5 m
    (MV, 2.0),  # 7.00 px per cell, spot centres off the pixel grid
    (dict(object_distance_m=1.0, lens_focal_m=0.05, sensor_distance_m=0.04, wavelength_m=550e-9,
          pixel_pitch_m=5e-6, pinhole_m=208.333e-6, sensor_cols=512, sensor_rows=512), 1.0),
    ("paper", 1.0), ("paper", 6.0)])  # 8.60 and 8.07 px per cell
def test_depth_fisher_against_numpy(tmp_path, camera, u):
    # pinmask's exact PSF with a box kernel draws each spot as the numpy model does (the box of
    # side d |M(u)| / w pixels at its Eq. (3) centre, integrated over the pixels), at any u, so
    # the two Fisher informations must agree.
    cam = pinmask.paper_camera() if camera == "paper" else pinmask.Camera(**camera)
    m = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=cam, kernel="box")
    path = tmp_path / "m.mask.json"
    m.save(str(path))
    mj = ds.load(path)
    f = pinmask.depth_fisher(m, u, photons=20000, read_noise=3, rows=320, cols=320)
    t, dt = 1 / u, f["one_pixel_inverse_per_m"] / 20
    mu = lambda tt: 20000 * ds.exact_psf(mj, 1 / tt, 320, 320)
    d = (mu(t + dt) - mu(t - dt)) / (2 * dt)
    info = float(np.sum(d * d / (mu(t) + 9.0)))
    assert f["fisher_inverse_m2"] == pytest.approx(info, rel=0.01)
    assert f["crb_distance_m"] == pytest.approx(u * u / math.sqrt(info), rel=0.01)
    o = mj["optics"]
    assert f["one_pixel_inverse_per_m"] == pytest.approx(
        o["pixel_pitch_m"] / (o["sensor_distance_m"] * 32 * o["pinhole_m"]), rel=1e-12)


def test_depth_fisher_refusals(tmp_path):
    m = _mask(tmp_path, pinmask.Camera(**MV))
    with pytest.raises(ValueError, match="photons"):
        pinmask.depth_fisher(m, 0.5, photons=0)
    with pytest.raises(ValueError, match="read_noise"):
        pinmask.depth_fisher(m, 0.5, read_noise=-1)
    with pytest.raises(ValueError, match="object_distance_m"):
        pinmask.depth_fisher(m, math.inf)


def test_ctrl_c_writes_the_planes_done(cli, tmp_path):
    import os
    import signal
    import subprocess
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    cap = tmp_path / "c.npy"
    np.save(cap, np.random.default_rng(1).random((512, 512)).astype(np.float32))
    out = tmp_path / "o"
    p = subprocess.Popen([cli.exe, "depthmap", str(cap), "--mask", str(mask), "--from", "0.4m",
                          "--to", "2m", "--steps", "400", "-o", str(out), "--json"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=dict(os.environ, PINMASK_WISDOM="off"))
    for line in p.stderr:  # the first progress line: one plane is done
        if "planes" in line and "/400" in line:
            break
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 0, stderr
    s = json.loads(stdout)
    assert s["interrupted"] and 1 <= s["planes_done"] < 400
    assert len(s["planes"]) == s["planes_done"]
    assert _read(out / "depth.tif").shape == (512, 512)
