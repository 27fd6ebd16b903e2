"""The depth figure as a design figure: score's and compare's `depth` group and search's depth
term. The keys are checked against the Fisher information summed in numpy over the independent
exact-geometry model of depth_scenes.py (box spots, as pinmask's box kernel draws them), for
two cameras; the search's per-cell sum against score's exact figure; weight 0 against the
search without the term, byte for byte."""
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
FWHM = 2.0 * math.sqrt(2.0 * math.log(2.0))


def _box_mask(tmp_path, camera, grid=16, holes=20, name="m"):
    cam = pinmask.paper_camera() if camera == "paper" else pinmask.Camera(**camera)
    m = pinmask.generate(family="random", grid=grid, holes=holes, spacing=2, tiles=2, seed=3,
                         camera=cam, kernel="box")
    path = tmp_path / f"{name}.mask.json"
    m.save(str(path))
    return m, path


def _numpy_figures(mj, u_from, u_to, photons_per_pinhole, read_noise):
    """The depth keys in numpy: 3 distances equally spaced in 1/u, the Fisher information of
    t = 1/u by a central difference of a twentieth of the one-pixel step, worst over them."""
    o, pat = mj["optics"], mj["pattern"]
    rows, cols = o["sensor_px"][1], o["sensor_px"][0]
    k = len(pat["pinholes"])
    photons = photons_per_pinhole * k
    nt = pat["n"] * max(pat["tiles"])
    dt = o["pixel_pitch_m"] / (o["sensor_distance_m"] * nt * o["pinhole_m"]) / 20
    worst_rel, worst_fwhm, worst_u = 0.0, 0.0, None
    for t in np.linspace(1 / u_from, 1 / u_to, 3):
        mu = lambda tt: photons * ds.exact_psf(mj, 1 / tt, rows, cols)  # noqa: E731
        d = (mu(t + dt) - mu(t - dt)) / (2 * dt)
        info = float(np.sum(d * d / (mu(t) + read_noise ** 2)))
        u = 1 / t
        sigma_u = u * u / math.sqrt(info)
        if sigma_u / u > worst_rel:
            worst_rel, worst_u = sigma_u / u, u
        worst_fwhm = max(worst_fwhm, FWHM * sigma_u)
    return worst_rel, worst_fwhm, worst_u


@pytest.mark.parametrize("camera,u_from,u_to", [(MV, 0.4, 2.0), ("paper", 1.0, 6.0)])
def test_score_depth_keys_against_numpy(tmp_path, camera, u_from, u_to):
    m, path = _box_mask(tmp_path, camera)
    out = pinmask.score([m], metrics="depth", photons=[200, 1000], read_noise=3,
                        depth_from=u_from, depth_to=u_to)
    row = out["masks"][0]
    assert row["depth_from_m"] == u_from and row["depth_to_m"] == u_to
    mj = ds.load(path)
    for p in (200, 1000):
        rel, fwhm, worst = _numpy_figures(mj, u_from, u_to, p, 3.0)
        assert row[f"depth_crb_rel_ph{p}"] == pytest.approx(rel, rel=0.01)
        assert row[f"depth_axial_fwhm_m_ph{p}"] == pytest.approx(fwhm, rel=0.01)
        assert row[f"depth_worst_distance_m_ph{p}"] == pytest.approx(worst, rel=1e-9)
    # More light, a tighter bound.
    assert row["depth_crb_rel_ph1000"] < row["depth_crb_rel_ph200"]


def test_score_depth_default_range_and_cli_parity(cli, tmp_path):
    m, path = _box_mask(tmp_path, MV, grid=8, holes=6)
    p = pinmask.score([str(path)], metrics=["depth", "sidelobes"], photons=500)["masks"][0]
    u = MV["object_distance_m"]  # the working distance: u / 2 .. 2 u
    assert p["depth_from_m"] == pytest.approx(u / 2) and p["depth_to_m"] == pytest.approx(2 * u)
    c = json.loads(cli.run("score", path, "--metrics", "depth,sidelobes", "--photons", "500",
                           "--json").stdout)["masks"][0]
    c["mask"] = p["mask"]
    assert c == p


def test_depth_range_flags_take_lengths_with_units(cli, tmp_path):
    # --depth-from/--depth-to read lengths as every other length flag does; a plain number is
    # metres. The same range in millimetres, metres and plain numbers gives the same row.
    _, path = _box_mask(tmp_path, MV, grid=8, holes=6)
    rows = []
    for lo, hi in (("400mm", "2m"), ("0.4m", "2000mm"), ("0.4", "2")):
        rows.append(json.loads(cli.run("score", path, "--metrics", "depth", "--photons", "500",
                                       "--depth-from", lo, "--depth-to", hi,
                                       "--json").stdout)["masks"][0])
    assert rows[0]["depth_from_m"] == pytest.approx(0.4, rel=1e-15)
    assert rows[0]["depth_to_m"] == pytest.approx(2.0, rel=1e-15)
    assert rows[0] == rows[1] == rows[2]


def test_compare_depth_equals_score(tmp_path):
    m, path = _box_mask(tmp_path, MV, grid=8, holes=6)
    s = pinmask.score([m], metrics="depth", photons=300, depth_from=0.3, depth_to=1.0)
    c = pinmask.compare([m], photons=300, depth=True, depth_from=0.3, depth_to=1.0,
                        scenes=["letter-R"], tv_iterations=5)
    for k in ("depth_crb_rel_ph300", "depth_axial_fwhm_m_ph300", "depth_from_m"):
        assert c["masks"][0][k] == s["masks"][0][k], k


def test_depth_refusals(tmp_path):
    m, _ = _box_mask(tmp_path, MV, grid=8, holes=6)
    with pytest.raises(ValueError, match="photons"):
        pinmask.score([m], metrics="depth")  # Gaussian noise has no photon count
    with pytest.raises(ValueError, match="depth_from"):
        pinmask.score([m], metrics="depth", photons=100, depth_from=-1, depth_to=2)
    with pytest.raises(ValueError, match="depth_to"):
        pinmask.score([m], metrics="depth", photons=100, depth_from=2, depth_to=1)
    with pytest.raises(ValueError, match="depth_from"):
        pinmask.score([m], metrics="depth", photons=100, depth_from=0.01, depth_to=1)  # < f'
    with pytest.raises(ValueError, match="depth_from"):
        pinmask.score([m], metrics="analytic", photons=100, depth_from=0.3, depth_to=1)
    with pytest.raises(ValueError, match="depth_weight"):
        pinmask.search(camera=pinmask.Camera(**MV), grid=8, holes=6, evals=10, depth_weight=1)
    with pytest.raises(ValueError, match="depth_weight"):
        pinmask.search(camera=pinmask.Camera(**MV), grid=8, holes=6, evals=10, photons=100,
                       depth_weight=-1)


def _search(tmp_path, name, *extra, cli):
    out = tmp_path / name
    cli.run("search", "--sensor", "256x256", "--grid", "8", "--holes", "6", "--tiles", "2",
            "--kernel", "box", "--evals", "400", "--seed", "2", "--top", "2", "--threads", "1",
            "--photons", "300", "--read-noise", "3", "--no-rerank", "--quiet", "-o", out, *extra)
    return out


def test_search_depth_weight(cli, tmp_path):
    cam = ["--object-distance", "0.5", "--lens-focal", "25mm", "--sensor-distance", "20mm",
           "--pixel-pitch", "3.45um", "--pinhole", "115um", "--wavelength", "530nm"]
    base = _search(tmp_path, "base", *cam, cli=cli)
    zero = _search(tmp_path, "zero", *cam, "--depth-weight", "0", cli=cli)
    for f in sorted(p.name for p in base.iterdir()):
        if f == "timing.csv":
            continue  # wall clock
        assert (base / f).read_bytes() == (zero / f).read_bytes(), f
    heavy = _search(tmp_path, "heavy", *cam, "--depth-weight", "20", cli=cli)
    m0 = pinmask.load_mask(str(base / "rank-1.mask.json"))
    m1 = pinmask.load_mask(str(heavy / "rank-1.mask.json"))
    assert sorted(map(tuple, m0.pattern.pinholes)) != sorted(map(tuple, m1.pattern.pinholes))
    terms = json.loads((heavy / "rank-1.mask.json").read_text())["provenance"]["scores"]
    assert "depth_crb_rel" in terms and "depth_crb_rel" not in json.loads(
        (base / "rank-1.mask.json").read_text())["provenance"]["scores"]
    cfg = json.loads((heavy / "search.config.json").read_text())
    assert cfg["weights"]["depth"] == 20 and cfg["depth_range"] == {"from_m": 0, "to_m": 0}
    # The exact figure (score) of the two masks: the weighted search's is better.
    s = pinmask.score([m0, m1], metrics="depth,analytic", photons=300, read_noise=3)["masks"]
    assert s[1]["depth_crb_rel_ph300"] < s[0]["depth_crb_rel_ph300"]
    # The search's per-cell sum against the exact figure: box spots one pitch wide and the
    # spacing rule of 2 cells, so no two open spots share a pixel and the sum is exact.
    assert terms["depth_crb_rel"] == pytest.approx(s[1]["depth_crb_rel_ph300"], rel=1e-9)
    # The config repeats the run.
    again = tmp_path / "again"
    cli.run("search", "--config", heavy / "search.config.json", "--quiet", "-o", again)
    assert (again / "rank-1.mask.json").read_bytes() == (heavy / "rank-1.mask.json").read_bytes()
