"""The photon noise model, scene priors, the optics working distance and check's sidecar: the
module against the CLI on the same inputs (same numbers: one library call each), and its
exceptions against the CLI's messages."""
import json
import math
import re

import numpy as np
import pytest

import pinmask

# The command line's flags and the module's keywords for the same settings: a library message
# names the setting by its field, which the CLI spells as the flag and the module as the keyword.
KEYWORD_OF_FLAG = {"--snr": "snr_db", "--photons": "photons", "--read-noise": "read_noise",
                   "--dark-current": "dark_current", "--full-well": "full_well", "--bits": "bits",
                   "--optical-density": "optical_density", "--prior": "prior",
                   "--prior-scenes": "prior_scenes", "--tone": "tone", "--shape": "shape",
                   "--frame": "frame", "--no-sidecar": "no_sidecar"}


def as_keywords(cli_message):
    """The CLI's message as the module words it: every flag spelled as its keyword."""
    def keyword(m):
        assert m.group(0) in KEYWORD_OF_FLAG, m.group(0)
        return KEYWORD_OF_FLAG[m.group(0)]
    return re.sub(r"--[a-z][a-z-]*", keyword, cli_message)

# The photon model with every sensor stage, two levels: (CLI flags, module arguments, keys).
PHOTON_CLI = ["--photons", "200,2000", "--read-noise", "3", "--dark-current", "0.5",
              "--full-well", "30000", "--bits", "12", "--optical-density", "3"]
PHOTON_PY = dict(photons=[200, 2000], read_noise=3, dark_current=0.5, full_well=30000, bits=12,
                 optical_density=3)
PHOTON_KEYS = ["ph200", "ph2000"]
LEVEL_FIELDS = ["analytic_wiener_psnr_db_", "analytic_mmse_psnr_db_",
                "analytic_wiener_nsr_", "sim_wiener_psnr_db_", "sim_wiener_ssim_",
                "sim_wiener_nsr_", "sim_tv_psnr_db_", "sim_tv_ssim_", "sim_tv_lambda_"]
ROW_KEYS = ["analytic_mmse_psnr_db", "analytic_wiener_psnr_db", "sim_wiener_psnr_db",
            "sim_wiener_ssim", "sim_tv_psnr_db", "sim_tv_ssim", "geometry_hash"]


def same(a, b):
    if b is None:  # the CLI writes null for an infinite value
        return math.isinf(a) or math.isnan(a)
    return a == b


def assert_rows_equal(row, cli_row, level_keys):
    for k in ROW_KEYS:
        assert same(row[k], cli_row.get(k)), (k, row[k], cli_row.get(k))
    for level in level_keys:
        for f in LEVEL_FIELDS:
            assert same(row[f + level], cli_row[f + level]), (f + level, row[f + level],
                                                              cli_row[f + level])


@pytest.fixture
def prior_images(tmp_path):
    """Two scene images for the 'files' prior (resampled to the period by the library)."""
    paths = []
    for i, name in enumerate(["siemens-star", "usaf"]):
        p = tmp_path / f"prior{i}.npy"
        pinmask.write_image(str(p), pinmask.scene(name, 96, 80))
        paths.append(str(p))
    return paths


def test_metrics_photon_model_equals_cli_compare(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", *PHOTON_CLI, "--tv-iters", "20",
                           "--json").stdout)
    row = pinmask.metrics(str(tmp_path / "m.mask.json"), tv_iterations=20, **PHOTON_PY)
    assert_rows_equal(row, j["masks"][0], PHOTON_KEYS)
    # The unsuffixed figures are the first level's.
    assert row["sim_wiener_psnr_db"] == row["sim_wiener_psnr_db_ph200"]
    # More photons, less noise: a better analytic figure.
    assert row["analytic_wiener_psnr_db_ph2000"] > row["analytic_wiener_psnr_db_ph200"]


@pytest.mark.parametrize("cli_prior,py_prior", [
    (["--prior", "stars", "--prior-scenes", "5"], dict(prior="stars", prior_scenes=5)),
    (["--prior", "natural", "--prior-scenes", "4"], dict(prior="natural", prior_scenes=4)),
])
def test_metrics_prior_equals_cli_compare(cli, tmp_path, mask7, cli_prior, py_prior):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "--snr", "20,40", *cli_prior,
                           "--tv-iters", "20", "--json").stdout)
    row = pinmask.metrics(str(tmp_path / "m.mask.json"), snr_db=[20, 40], tv_iterations=20,
                          **py_prior)
    assert_rows_equal(row, j["masks"][0], ["snr20", "snr40"])


TEXT_PRIOR_SCRIPT = """
import json, sys
import pinmask
row = pinmask.metrics(sys.argv[1], snr_db=[20, 40], tv_iterations=20, prior="text",
                      prior_scenes=3)
print(json.dumps(row))
"""


def test_metrics_text_prior_equals_cli_compare(cli, tmp_path, mask7):
    """The text prior in a fresh interpreter (as each CLI run is): see the next test for why."""
    import subprocess
    import sys
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "--snr", "20,40", "--prior", "text",
                           "--prior-scenes", "3", "--tv-iters", "20", "--json").stdout)
    p = subprocess.run([sys.executable, "-c", TEXT_PRIOR_SCRIPT, str(tmp_path / "m.mask.json")],
                       capture_output=True, text=True, timeout=300, check=True)
    row = json.loads(p.stdout)
    assert_rows_equal(row, j["masks"][0], ["snr20", "snr40"])


# The text prior draws the same pages whatever Cairo drew before in the process (a report
# turns metric hinting off; optimize/simulate/scene_text sets every font option itself).
def test_text_prior_same_after_a_report(tmp_path):
    import subprocess
    import sys
    script = """
import sys
import pinmask
m = pinmask.generate(seed=7)
if sys.argv[1] == "report-first":
    pinmask.compare([m], report=sys.argv[2], tv_iterations=5)
print(pinmask.metrics(m, prior="text", prior_scenes=2, tv_iterations=5)["analytic_wiener_psnr_db"])
"""
    values = [subprocess.run([sys.executable, "-c", script, order, str(tmp_path / "r.pdf")],
                             capture_output=True, text=True, timeout=300, check=True).stdout
              for order in ["text-only", "report-first"]]
    assert values[0] == values[1]


def test_metrics_prior_files_equals_cli_and_score(cli, tmp_path, mask7, prior_images):
    mask7.save(str(tmp_path / "m.mask.json"))
    files = ",".join(prior_images)
    j = json.loads(cli.run("compare", "m.mask.json", "--prior", files, "--tv-iters", "20",
                           "--json").stdout)
    row = pinmask.metrics(str(tmp_path / "m.mask.json"), prior=prior_images, tv_iterations=20)
    assert_rows_equal(row, j["masks"][0], ["snr30"])
    # One comma-separated string is the same prior as the list.
    assert pinmask.metrics(mask7, prior=files, tv_iterations=20)["analytic_wiener_psnr_db"] == \
        row["analytic_wiener_psnr_db"]
    # score computes the analytic figure with the same prior: the same number.
    s = json.loads(cli.run("score", "m.mask.json", "--snr", "30", "--nsr", "tuned", "--prior",
                           files, "--json").stdout)["masks"][0]
    assert row["analytic_wiener_psnr_db"] == s["analytic_wiener_psnr_db_snr30"]
    # A different prior gives a different figure (the argument is used).
    assert pinmask.metrics(mask7, tv_iterations=20)["analytic_wiener_psnr_db"] != \
        row["analytic_wiener_psnr_db"]


def test_compare_photon_model_and_prior_equal_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    pinmask.generate(seed=8).save(str(tmp_path / "o.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "o.mask.json", *PHOTON_CLI, "--prior",
                           "stars", "--tv-iters", "20", "--report", "cli.pdf",
                           "--json").stdout)
    out = pinmask.compare([str(tmp_path / "m.mask.json"), str(tmp_path / "o.mask.json")],
                          tv_iterations=20, prior="stars", report=str(tmp_path / "py.pdf"),
                          **PHOTON_PY)
    assert len(out["masks"]) == 2
    for row, cli_row in zip(out["masks"], j["masks"]):
        assert_rows_equal(row, cli_row, PHOTON_KEYS)
    assert (tmp_path / "py.pdf").read_bytes()[:5] == b"%PDF-"


def test_search_photon_model_and_prior_same_masks_as_cli(cli, tmp_path):
    cli.run("search", "--preset", "paper", "--grid", "16", "--holes", "20", "--evals", "150",
            "--threads", "1", "--seed", "4", "--top", "2", "--no-rerank", "--photons", "500",
            "--read-noise", "2", "--full-well", "40000", "--bits", "10", "--prior", "stars",
            "--prior-scenes", "2", "-o", "runs")
    r = pinmask.search(grid=16, holes=20, evals=150, threads=1, seed=4, top=2, rerank_scenes=[],
                       photons=500, read_noise=2, full_well=40000, bits=10, prior="stars",
                       prior_scenes=2)
    assert len(r["masks"]) == 2
    for i, m in enumerate(r["masks"]):
        assert m.to_json() == (tmp_path / "runs" / f"rank-{i + 1}.mask.json").read_text()
    # The noise model is used: Gaussian noise finds a different objective.
    g = pinmask.search(grid=16, holes=20, evals=150, threads=1, seed=4, top=2, rerank_scenes=[],
                       prior="stars", prior_scenes=2)
    assert g["ranked"][0]["objective"] != r["ranked"][0]["objective"]


@pytest.mark.parametrize("cli_args,kwargs", [
    (["--read-noise", "3"], dict(read_noise=3)),
    (["--photons", "100", "--bits", "8"], dict(photons=100, bits=8)),
    (["--photons", "-5"], dict(photons=-5)),
    (["--photons", "100", "--optical-density", "-1"], dict(photons=100, optical_density=-1)),
    (["--prior", "sky"], dict(prior="sky")),
    (["--prior", "natural", "--prior-scenes", "0"], dict(prior="natural", prior_scenes=0)),
])
def test_noise_and_prior_errors_same_message_as_cli(cli, tmp_path, mask7, cli_args, kwargs):
    mask7.save(str(tmp_path / "m.mask.json"))
    msg = as_keywords(cli.error("compare", "m.mask.json", *cli_args))
    with pytest.raises(ValueError) as e:
        pinmask.metrics(mask7, **kwargs)
    assert str(e.value) == msg
    with pytest.raises(ValueError) as e:
        pinmask.compare([mask7], **kwargs)
    assert str(e.value) == msg


def test_search_noise_errors_same_message_as_cli(cli):
    msg = cli.error("search", "--evals", "5", "--photons", "100,200", "-o", "runs")
    assert msg.startswith("--snr/--photons: ")
    with pytest.raises(ValueError) as e:
        pinmask.search(evals=5, photons=[100, 200])
    assert str(e.value) == as_keywords(msg)
    # Both models at once: CLI11 refuses it before any command code ("--snr excludes
    # --photons"); the module names both keywords.
    with pytest.raises(ValueError, match="^snr_db = 30: cannot be combined with photons"):
        pinmask.metrics(pinmask.generate(), snr_db=30, photons=100)
    with pytest.raises(ValueError, match="^snr_db = 'thirty'"):
        pinmask.search(evals=5, snr_db="thirty")
    with pytest.raises(ValueError, match="^photons = '': needs at least one item"):
        pinmask.metrics(pinmask.generate(), photons=[])


@pytest.mark.parametrize("args,kwargs", [
    (["--preset", "paper"], {}),
    (["--preset", "paper", "--object-distance", "2m", "--lsi-tolerance", "0.5"],
     dict(camera=pinmask.Camera(object_distance_m=2.0), lsi_tolerance_px=0.5)),
    (["--preset", "paper", "--object-distance", "inf", "--lens-focal", "55mm"],
     dict(camera=pinmask.Camera(object_distance_m="inf", lens_focal_m="55mm"))),
])
def test_optics_working_distance_equals_cli_design_json(cli, args, kwargs):
    j = json.loads(cli.run("design", *args, "--json").stdout)
    d = pinmask.optics(**kwargs)
    wd_keys = ["whole_pixels_per_cell_at_u", "pinhole_for_pixels_per_cell_m", "period_at_u_px",
               "lsi_mismatch_at_u_px", "optimum_pinhole_lensless_m",
               "optimum_pinhole_with_lens_m", "spot_spread_cells", "spot_spreads_beyond_cell",
               "kernel_reason", "kernel_warnings", "kernel_model"]
    # The faces spell fields their own way: psf's --energy is energy_fraction in Python, and
    # each names where the setting lives when design / optics() lack it.
    def unspelled(warnings, setting, owners):
        for w in warnings:
            if setting in w:
                assert owners in w, (w, owners)
        where = r" \((?:a flag|a keyword) of .*?, not of (?:design|optics\(\))\)"
        return [re.sub(where, "", w).replace(setting, "energy_fraction") for w in warnings]
    j["kernel_warnings"] = unspelled(j["kernel_warnings"], "--energy",
                                     "(a flag of pinmask psf")
    d["kernel_warnings"] = unspelled(d["kernel_warnings"], "energy_fraction",
                                     "not of optics()")
    for k in wd_keys:  # infinite values are None in both, with their notes
        assert d[k] == j[k], (k, d[k], j[k])
    assert d["object_distance_range_m"] == j["object_distance_range_m"]
    assert d["notes"] == j["notes"]
    # Every number design --json prints is in optics() with the same value.
    numbers = [k for k, v in j.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    assert numbers and all(k in d and d[k] == j[k] for k in numbers), \
        [k for k in numbers if k not in d or d[k] != j[k]]


def test_optics_working_distance_paper_numbers():
    d = pinmask.optics()
    # design/optics/working_distance.hpp: d(N, u) = N w / |1 - f/f' + f/u|, the optimum 1.56 sqrt(lambda f).
    c = pinmask.paper_camera()
    m_u = abs(1 - c.sensor_distance_m / c.lens_focal_m + c.sensor_distance_m / c.object_distance_m)
    n = d["whole_pixels_per_cell_at_u"]
    rel = 1e-12  # two evaluations of one closed form in double precision
    assert d["pinhole_for_pixels_per_cell_m"] == pytest.approx(n * c.pixel_pitch_m / m_u, rel=rel)
    assert d["optimum_pinhole_lensless_m"] == pytest.approx(
        1.56 * math.sqrt(c.wavelength_m * c.sensor_distance_m), rel=rel)
    assert d["period_at_u_px"] == pytest.approx(16 * c.pinhole_m * m_u / c.pixel_pitch_m, rel=rel)
    with pytest.raises(ValueError, match="^lsi_tolerance_px = "):
        pinmask.optics(lsi_tolerance_px=0)


def test_check_reads_the_export_sidecar_like_cli(cli, tmp_path, mask7, monkeypatch):
    # The sidecar records the mask path as given to export (relative to the CLI's folder).
    monkeypatch.chdir(tmp_path)
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", "--format", "gds,dxf", "--tone", "dark", "--mirror",
            "--frame", "2mm", "--marks", "--label", "--shape", "circle", "--no-psf", "-o", "fab")
    for name in ["m.gds", "m.dxf"]:
        path = str(tmp_path / "fab" / name)
        j = json.loads(cli.run("check", path, "--json").stdout)
        got = json.loads(json.dumps(pinmask.check(path)))
        assert got == j, name
        assert got["clean"] and got["comparison"]["ok"]
        assert got["settings"].startswith("from ") and got["settings"].endswith("m.export.json")
        assert got["tone"] == "dark"
    path = str(tmp_path / "fab" / "m.gds")
    # A given setting must agree with the sidecar: the CLI's message.
    for cli_args, kwargs in [(["--tone", "clear"], dict(tone="clear")),
                             (["--shape", "square"], dict(shape="square")),
                             (["--frame", "1mm"], dict(frame="1mm"))]:
        msg = cli.error("check", path, *cli_args)
        with pytest.raises(ValueError) as e:
            pinmask.check(path, **kwargs)
        assert str(e.value) == as_keywords(msg)
    # Ignoring the sidecar: the settings come from the arguments again (the CLI's --no-sidecar).
    p = cli.run("check", path, "--no-sidecar", "--mask", "m.mask.json", "--shape", "circle",
                "--frame", "2mm", "--json", expect=(0, 1))
    got = json.loads(json.dumps(pinmask.check(path, mask="m.mask.json", shape="circle",
                                              frame="2mm", no_sidecar=True)))
    assert got == json.loads(p.stdout)
    assert got["clean"] == (p.returncode == 0)
    assert got["settings"].startswith("from the flags")


# Camera files: the module writes the bytes `design --save-camera` writes, and a camera file
# read by the module gives the mask `generate --camera FILE` gives. The NIR camera of
# docs/fabrication.md, not the paper's.
NIR_FLAGS = ["--pixel-pitch", "5.86um", "--sensor", "1920x1200", "--lens-focal", "75mm",
             "--sensor-distance", "45mm", "--object-distance", "1.2m", "--wavelength", "850nm",
             "--pinhole", "350um"]


def test_camera_file_equals_design_save_camera(cli, tmp_path):
    cli.run("design", *NIR_FLAGS, "--save-camera", "cli.camera.json")
    cam = pinmask.Camera(pixel_pitch_m="5.86um", sensor_cols=1920, sensor_rows=1200,
                         lens_focal_m="75mm", sensor_distance_m="45mm", object_distance_m="1.2m",
                         wavelength_m="850nm", pinhole_m="350um")
    pinmask.save_camera(cam, str(tmp_path / "py.camera.json"))
    assert (tmp_path / "py.camera.json").read_bytes() == \
        (tmp_path / "cli.camera.json").read_bytes()
    assert cam.to_json() == (tmp_path / "cli.camera.json").read_text()
    loaded = pinmask.load_camera(str(tmp_path / "cli.camera.json"))
    assert loaded == cam
    assert "wavelength_m=8.5e-07" in repr(loaded)  # not rounded to six decimals
    cli.run("generate", "--camera", "cli.camera.json", "--grid", "12", "--holes", "9",
            "--seed", "3", "-o", "cli.mask.json")
    mask = pinmask.generate(camera=loaded, grid=12, holes=9, seed=3)
    assert mask.to_json() == (tmp_path / "cli.mask.json").read_text()


def test_camera_file_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.camera.json"
    bad.write_text('{"format": "pinmask-camera", "version": 99}')
    with pytest.raises(ValueError, match="bad.camera.json"):
        pinmask.load_camera(str(bad))


def test_search_holes_range_same_masks_as_cli(cli, tmp_path):
    cli.run("search", "--preset", "paper", "--grid", "16", "--holes", "8..14", "--evals", "200",
            "--threads", "1", "--seed", "5", "--top", "2", "--no-rerank", "-o", "runs")
    r = pinmask.search(grid=16, holes="8..14", evals=200, threads=1, seed=5, top=2,
                       rerank_scenes=[])
    assert len(r["masks"]) == 2
    for i, m in enumerate(r["masks"]):
        assert m.to_json() == (tmp_path / "runs" / f"rank-{i + 1}.mask.json").read_text()
    counts = {len(m.pattern.pinholes) for m in r["masks"]}
    assert all(8 <= k <= 14 for k in counts)
    # The range's messages are the CLI's, in Python spelling.
    msg = as_keywords_holes(cli.error("search", "--holes", "9..4", "--evals", "5", "-o", "bad"))
    with pytest.raises(ValueError) as e:
        pinmask.search(holes="9..4", evals=5)
    assert str(e.value) == msg
    with pytest.raises(ValueError, match="^holes = 2.5"):
        pinmask.search(holes=2.5, evals=5)


def as_keywords_holes(cli_message):
    return cli_message.replace("--holes", "holes").replace("--evals", "evals")
