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


@pytest.mark.parametrize("camera,frm,to,truth,bound,within", [
    ("mv", 0.4, 2.0, 0.45, 2.0, 0.1), ("mv", 0.4, 2.0, 1.5, 1.0, 0.7),
    ("paper", 1.0, 10.0, 2.0, 1.5, 0.65), ("paper", 1.0, 10.0, 5.0, 1.5, 0.8)])
def test_whole_capture_depth_of_one_plane(cli, tmp_path, camera, frm, to, truth, bound, within):
    cam = pinmask.Camera(**MV) if camera == "mv" else pinmask.paper_camera()
    mask = _mask(tmp_path, cam)
    row = ds.measure(_runner(cli, tmp_path, mask), _read, mask, [truth], frm, to, 16, 384,
                     2000.0, 1, baseline=False)
    # Measured 1.70 / 0.54 / 0.88 / 0.60 plane spacings (docs/depth.md).
    assert row["capture_error_planes"] <= bound
    # The map with the default smoothing: 16 / 81 / 78 / 90 % of the pixels within one plane
    # spacing (docs/depth.md; 15 / 48 / 57 / 62 % without smoothing).
    assert row["within_spacing"] >= within


# docs/depth.md's three-plane rows. Close range: RMS 2.69 plane spacings, 26 % within one
# spacing (chance: about 19 %; 2.74 and 25 % without smoothing); all-in-focus 16.88 dB against
# 17.20 dB for the best single-plane decode. Paper camera: RMS 2.68 plane spacings, 32 % within
# one spacing (3.09 and 30 % without smoothing); all-in-focus 17.99 dB against 17.91 dB.
@pytest.mark.parametrize("camera,planes,frm,to,rms,within,aif_margin", [
    ("mv", [0.45, 0.7, 1.5], 0.4, 2.0, 2.9, 0.22, 0.6),
    ("paper", [1.5, 3.0, 8.0], 1.0, 10.0, 3.0, 0.28, 0.3)], ids=["close-range", "paper-camera"])
def test_three_planes_row(cli, tmp_path, camera, planes, frm, to, rms, within, aif_margin):
    mask = _mask(tmp_path, pinmask.Camera(**MV) if camera == "mv" else pinmask.paper_camera())
    row = ds.measure(_runner(cli, tmp_path, mask), _read, mask, planes, frm, to, 16, 384, 2000.0,
                     1)
    assert row["rms_planes"] <= rms
    assert row["within_spacing"] >= within
    assert row["aif_psnr_db"] >= row["single_best_psnr_db"] - aif_margin


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
    arrays = {"depth_m", "confidence", "cost_margin", "all_in_focus", "label"}
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


def _box_mask(tmp_path, camera):
    m = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=camera, kernel="box")
    path = tmp_path / "box.mask.json"
    m.save(str(path))
    return path


def _write_stack(folder, mask_json, distances, size):
    """The PSFs of the numpy model (depth_scenes.exact_psf, never pinmask's code) at the given
    distances, as float64 .npy files listed by folder/psf_stack.json (in reverse order: the
    reader sorts by distance)."""
    folder.mkdir()
    planes = []
    for k, u in enumerate(distances):
        np.save(folder / f"psf_{k}.npy", ds.exact_psf(mask_json, u, size, size))
        planes.append({"object_distance_m": u, "psf": f"psf_{k}.npy"})
    (folder / "psf_stack.json").write_text(json.dumps(
        {"format": "pinmask-psf-stack", "version": 1, "planes": planes[::-1]}))


@pytest.mark.parametrize("camera,frm,to,bands", [
    ("mv", 0.4, 2.0, [0.5, 1.2]), ("paper", 1.0, 10.0, [1.5, 5.0])])
def test_psf_stack_of_an_independent_model_gives_the_mask_map(cli, tmp_path, camera, frm, to,
                                                             bands):
    # With box spots pinmask's exact PSF is the numpy model's to rounding (docs/depth.md section
    # 8), so a stack of numpy PSFs at the sweep's distances must give --mask's map (with the
    # default smoothing).
    cam = pinmask.Camera(**MV) if camera == "mv" else pinmask.paper_camera()
    mask = _box_mask(tmp_path, cam)
    mj = ds.load(mask)
    size = 256
    capture, _, _, _ = ds.scene(mj, bands, size, size, 2000.0, 4)
    cap = tmp_path / "c.npy"
    np.save(cap, capture)
    a = json.loads(cli.run("depthmap", cap, "--mask", mask, "--from", f"{frm}m", "--to",
                           f"{to}m", "--steps", 8, "--window", 61, "-o", tmp_path / "a",
                           "--json").stdout)
    distances = [p["object_distance_m"] for p in a["planes"]]
    _write_stack(tmp_path / "stack", mj, distances, size)
    b = json.loads(cli.run("depthmap", cap, "--psf-stack", tmp_path / "stack", "--window", 61,
                           "-o", tmp_path / "b", "--json").stdout)
    assert b["psf_stack"] == str(tmp_path / "stack") and b["mask"] is None
    assert [p["object_distance_m"] for p in b["planes"]] == distances
    for pa, pb in zip(a["planes"], b["planes"]):
        assert pb["mean_cost"] == pytest.approx(pa["mean_cost"], rel=1e-9)
        assert pb["pixel_fraction"] == pa["pixel_fraction"]  # the same planes everywhere
    assert b["capture_depth_m"] == pytest.approx(a["capture_depth_m"], rel=1e-9)
    # Measured: the same label at every pixel, depths within 2e-14 (before the float32 files).
    da, db = _read(tmp_path / "a" / "depth.tif"), _read(tmp_path / "b" / "depth.tif")
    assert np.allclose(da, db, rtol=1e-6, atol=0)
    fa = _read(tmp_path / "a" / "all_in_focus.tif")
    fb = _read(tmp_path / "b" / "all_in_focus.tif")
    assert np.allclose(fa, fb, rtol=1e-5, atol=1e-6)
    # Python: a list of (distance, array) pairs gives the command's map.
    stack = [(u, ds.exact_psf(mj, u, size, size)) for u in distances]
    p = pinmask.depthmap(capture, psf_stack=stack, window=61)
    assert np.array_equal(p["depth_m"].astype(np.float32), db)
    assert p["smooth"] == b["smooth"] and p["psf_stack"] is None


def test_psf_stack_refusals_name_the_flag_and_keyword(cli, tmp_path):
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    cap = tmp_path / "c.npy"
    np.save(cap, np.random.default_rng(0).random((64, 64)))
    psf = np.zeros((16, 16))
    psf[8, 8] = 1.0
    folder = tmp_path / "s"
    folder.mkdir()
    np.save(folder / "p.npy", psf)

    def stack(planes):
        (folder / "psf_stack.json").write_text(json.dumps(
            {"format": "pinmask-psf-stack", "version": 1,
             "planes": [{"object_distance_m": u, "psf": f} for u, f in planes]}))
        return cli.error("depthmap", cap, "--psf-stack", folder, "--window", 15, "-o",
                         tmp_path / "o")

    assert stack([(1.0, "p.npy")]).startswith("--psf-stack ")
    assert "must be > 0" in stack([(1.0, "p.npy"), (-2.0, "p.npy")])
    assert "same distance" in stack([(1.0, "p.npy"), (1.0, "p.npy")])
    assert "--psf-stack" in stack([(1.0, "p.npy"), (2.0, "missing.npy")])
    assert "--mask" in cli.error("depthmap", cap, "--mask", mask, "--psf-stack", folder,
                                 "-o", tmp_path / "o")
    assert "--steps" in cli.error("depthmap", cap, "--psf-stack", folder, "--steps", 4,
                                  "-o", tmp_path / "o")
    assert not (tmp_path / "o").exists()
    cap64 = np.ones((64, 64))
    with pytest.raises(ValueError, match="psf_stack"):
        pinmask.depthmap(cap64, psf_stack=[(1.0, psf)], window=15)
    with pytest.raises(ValueError, match="psf_stack"):
        pinmask.depthmap(cap64, psf_stack=[(1.0, psf), (1.0, psf)], window=15)
    with pytest.raises(ValueError, match="psf_stack"):
        pinmask.depthmap(cap64, psf_stack=[(1.0, psf), (2.0, -psf)], window=15)
    with pytest.raises(ValueError, match="psf_stack"):
        pinmask.depthmap(cap64, psf_stack=[(1.0, psf), (2.0, np.ones((65, 8)))], window=15)
    with pytest.raises(ValueError, match="from_m"):
        pinmask.depthmap(cap64, psf_stack=[(1.0, psf), (2.0, psf)], from_m=1.0, window=15)
    with pytest.raises(ValueError, match="mask"):
        pinmask.depthmap(cap64, mask, psf_stack=[(1.0, psf), (2.0, psf)], window=15)
    with pytest.raises(ValueError, match="smooth"):
        pinmask.depthmap(cap64, mask, from_m=0.4, to_m=2.0, window=15, smooth=-1)


def test_smoothing_joins_the_labels(tmp_path):
    # smooth = 0 labels each pixel by its lowest cost alone; smooth > 0 changes labels on a noisy
    # two-plane scene, towards fewer steps between neighbours.
    mask = _mask(tmp_path, pinmask.Camera(**MV))
    capture, _, _, _ = ds.scene(ds.load(mask), [0.5, 1.2], 128, 128, 2000.0, 2)
    kw = dict(from_m=0.4, to_m=2.0, steps=6, window=31)
    wta = pinmask.depthmap(capture, str(mask), smooth=0, **kw)
    smooth = pinmask.depthmap(capture, str(mask), smooth=8, **kw)
    assert wta["smooth"] == 0 and smooth["smooth"] == 8
    assert not np.array_equal(wta["label"], smooth["label"])
    # The smoothed map has fewer label changes between neighbours.
    steps = lambda l: np.count_nonzero(np.diff(l, axis=0)) + np.count_nonzero(np.diff(l, axis=1))
    assert steps(smooth["label"]) < steps(wta["label"])
