"""Each capability's Python result is its command's --json: one library transaction, one io/
rendering, so `result.to_dict()` equals what the command prints for the same settings (the
library's words that name a setting are in each face's own spelling)."""
import json
import re

import numpy as np

import pinmask


def test_compare_equals_cli_json(cli, tmp_path, mask7, monkeypatch):
    mask7.save(str(tmp_path / "m.mask.json"))
    pinmask.generate(seed=8).save(str(tmp_path / "o.mask.json"))
    args = ["--scenes", "letter-R", "--tv-iters", "5", "--robust", "size=44um,jitter=2um",
            "--report", "r.svg"]
    j = json.loads(cli.run("compare", "m.mask.json", "o.mask.json", *args, "--json").stdout)
    cli_config = (tmp_path / "r.config.json").read_text()
    for f in j["report"] + [j["config"]]:
        (tmp_path / f).unlink()
    monkeypatch.chdir(tmp_path)
    out = pinmask.compare(["m.mask.json", "o.mask.json"], scenes=["letter-R"], tv_iterations=5,
                          robust="size=44um,jitter=2um", report="r.svg")
    assert out.to_dict() == j
    # The config beside the report is the same rendering, byte for byte.
    assert (tmp_path / "r.config.json").read_text() == cli_config


def test_compare_baselines_equal_cli_json(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "--baselines", "--baseline-count", "3",
                           "--scenes", "letter-R", "--tv-iters", "5", "--json").stdout)
    out = pinmask.compare([str(tmp_path / "m.mask.json")], baselines=True, baseline_count=3,
                          scenes=["letter-R"], tv_iterations=5)
    for row in j["masks"]:  # how a baseline was made names its settings: here as flags
        row["source"] = row["source"].replace("--family", "family").replace("--seed", "seed")
    j["masks"][0]["source"] = str(tmp_path / "m.mask.json")
    assert out.to_dict() == j
    assert out.baselines.mura.order == j["baselines"]["mura"]["order"]


MAPS = ("depth_m", "confidence", "cost_margin", "all_in_focus", "label")


def test_depthmap_equals_cli_json(cli, tmp_path, mask7, monkeypatch):
    """The summary of depthmap() is `depthmap --json`, and with output_dir the same files."""
    mask7.save(str(tmp_path / "m.mask.json"))
    rng = np.random.default_rng(5)
    np.save(tmp_path / "cap.npy", rng.random((48, 40)).astype(np.float32))
    args = ["--from", "2m", "--to", "inf", "--steps", "3", "--window", "9", "--smooth", "2"]
    j = json.loads(cli.run("depthmap", "cap.npy", "--mask", "m.mask.json", *args, "-o", "cli",
                           "--json").stdout)
    monkeypatch.chdir(tmp_path)
    out = pinmask.depthmap("cap.npy", mask="m.mask.json", from_m=2.0, to_m="inf", steps=3,
                           window=9, smooth=2, output_dir="py")
    assert {k: v for k, v in out.to_dict().items() if k not in MAPS} == j
    for name in j["files"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    # Nothing written: the same summary with no files.
    bare = pinmask.depthmap("cap.npy", mask="m.mask.json", from_m=2.0, to_m="inf", steps=3,
                            window=9, smooth=2)
    assert bare.files == [] and bare.planes == j["planes"]


def test_score_equals_cli_json(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    pinmask.generate(seed=8).save(str(tmp_path / "o.mask.json"))
    j = json.loads(cli.run("score", "m.mask.json", "o.mask.json", "--metrics",
                           "sidelobes,spectrum,analytic,wiener", "--scenes", "letter-R,usaf",
                           "--snr", "20,30", "--robust", "size=44um,jitter=2um", "--json").stdout)
    out = pinmask.score([str(tmp_path / "m.mask.json"), str(tmp_path / "o.mask.json")],
                        metrics="sidelobes,spectrum,analytic,wiener", scenes=["letter-R", "usaf"],
                        snr_db=[20, 30], robust="size=44um,jitter=2um")
    for row in j["masks"]:
        row["mask"] = str(tmp_path / row["mask"])
    assert out.to_dict() == j
    photons = json.loads(cli.run("score", "m.mask.json", "--metrics", "analytic", "--photons",
                                 "300", "--read-noise", "2", "--json").stdout)
    p = pinmask.score([mask7], metrics="analytic", photons=300, read_noise=2)
    photons["masks"][0]["mask"] = "mask 1"
    assert p.to_dict() == photons


def test_depth_equals_cli_json(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("depth", "m.mask.json", "--distances", "2m,6m,inf", "--photons", "50",
                           "--scenes", "letter-R", "--no-tv", "--json").stdout)
    out = pinmask.depth(mask7, distances=[2.0, 6.0, float("inf")], photons=50,
                        scenes=["letter-R"], tv=False)
    assert [r.to_dict() for r in out] == j
    assert out[2].object_distance_m is None  # inf, as null in the JSON


def test_optics_equals_cli_design_json(cli):
    """optics() is `design --json`: the paper's camera (both faces name it the preset default)."""
    j = json.loads(cli.run("design", "--preset", "paper", "--json").stdout)
    assert pinmask.optics().to_dict() == j
    # A distant object and no lens: infinities as null with their notes, in both.
    j = json.loads(cli.run("design", "--preset", "paper", "--object-distance", "inf",
                           "--lens-focal", "inf", "--pinhole", "440um", "--grid", "8", "--holes", "6",
                           "--json").stdout)
    out = pinmask.optics(pinmask.Camera(object_distance_m="inf", lens_focal_m="inf",
                                        pinhole_m="440um"), grid=8, holes=6)
    assert out.camera.object_distance_m is None and "object_distance_m" in out.notes
    # Where the camera values came from is each face's own word (a flag, the camera argument).
    assert set(out.input_sources.values()) == {"camera argument"}
    assert {k: v for k, v in out.to_dict().items() if k != "input_sources"} == \
        {k: v for k, v in j.items() if k != "input_sources"}


def test_optics_solved_equals_cli_design_json(cli, tmp_path):
    """A pinhole solved for whole pixels per cell and snapped to an export preset's grid."""
    flags = ["--pixel-pitch", "3.45um", "--sensor", "2448x2048", "--lens-focal", "25mm",
             "--sensor-distance", "20mm", "--object-distance", "2m", "--wavelength", "530nm"]
    j = json.loads(cli.run("design", *flags, "--pixels-per-cell", "12", "--vendor",
                           "film-plotter", "--spacing", "3", "--json").stdout)
    out = pinmask.optics(pinmask.Camera(pixel_pitch_m="3.45um", sensor_cols=2448,
                                        sensor_rows=2048, lens_focal_m="25mm",
                                        sensor_distance_m="20mm", object_distance_m="2m",
                                        wavelength_m="530nm"),
                         pixels_per_cell=12, vendor="film-plotter", spacing=3)
    solved = out.input_sources["d (pinhole)"]
    assert solved.startswith("solved") and j["input_sources"]["d (pinhole)"] == solved
    # psf's setting a warning names is in each face's spelling: --energy, energy_fraction.
    assert j["kernel_warnings"] and len(out.kernel_warnings) == len(j["kernel_warnings"])
    where = r" \((?:a flag|a keyword) of .*?, not of (?:design|optics\(\))\)"
    for d in (j, out):
        del d["input_sources"]
        d["kernel_warnings"] = [re.sub(where, "", w).replace("--energy", "energy_fraction")
                                for w in d["kernel_warnings"]]
    assert out.to_dict() == j


def test_export_mask_equals_cli_json(cli, tmp_path, mask7, monkeypatch):
    """export_mask() is `export --json`: the sidecar <stem>.export.json as written, PSF included."""
    mask7.save(str(tmp_path / "m.mask.json"))
    args = ["--format", "gds,dxf,svg", "--vendor", "film-plotter", "--shape", "circle",
            "--label", "--marks", "--units", "mm"]
    j = json.loads(cli.run("export", "m.mask.json", *args, "-o", "cli", "--json").stdout)
    monkeypatch.chdir(tmp_path)  # the mask path recorded as given, as the command records it
    out = pinmask.export_mask("m.mask.json", "py", formats=["gds", "dxf", "svg"],
                              vendor="film-plotter", shape="circle", label=True, marks=True,
                              units="mm")
    assert out.to_dict() == j
    assert out.to_dict() == json.loads((tmp_path / "py" / "m.export.json").read_text())
    assert [f.name for f in out.files] == ["m.gds", "m.dxf", "m.svg"]
    assert out.psf.files == ["m.psf.tiff", "m.psf.json"] and out.drc.clean


def test_check_equals_cli_json(cli, tmp_path, mask7, monkeypatch):
    """check() is `check --json` for each kind of input: a mask, a fabrication file with and
    without its sidecar or design, a picture against its design, and overridden rules."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", "--format", "gds,dxf,pdf,png", "--vendor", "film-plotter",
            "-o", "fab")
    (tmp_path / "lone").mkdir()
    (tmp_path / "lone" / "m.gds").write_bytes((tmp_path / "fab" / "m.gds").read_bytes())
    monkeypatch.chdir(tmp_path)
    cases = [
        (["m.mask.json"], {}),
        (["m.mask.json", "--vendor", "chrome", "--min-gap", "600um", "--list", "2"],
         dict(vendor="chrome", min_gap="600um", list=2)),
        (["fab/m.gds"], {}),
        (["fab/m.dxf", "--no-sidecar", "--mask", "m.mask.json", "--tone", "dark"],
         dict(no_sidecar=True, mask="m.mask.json", tone="dark")),
        (["fab/m.pdf"], {}),
        (["fab/m.png", "--min-feature", "1mm"], dict(min_feature="1mm")),
        (["lone/m.gds", "--min-spacing", "800um"], dict(min_spacing="800um")),
    ]
    for args, kwargs in cases:
        p = cli.run("check", *args, "--json", expect=(0, 1))
        j = json.loads(p.stdout)
        out = pinmask.check(args[0], **kwargs)
        assert out.to_dict() == j, args
        assert out.clean == (p.returncode == 0), args
    assert "picture" in pinmask.check("fab/m.pdf")
    # A Mask object is named as such where the command names its file.
    j = json.loads(cli.run("check", "m.mask.json", "--json").stdout)
    j["input"] = "python mask"
    assert pinmask.check(mask7).to_dict() == j


def test_search_equals_cli_json(cli, tmp_path):
    """search() is `search --json` with nothing written: output and the rows' paths None, the
    masks the command writes as values (rank-N.mask.json), and the run's timings its own."""
    flags = ["--grid", "8", "--holes", "5..7", "--evals", "300", "--threads", "1", "--seed", "4",
             "--top", "2", "--rerank-scenes", "letter-R", "--robust", "size=44um,jitter=2um",
             "--quiet"]
    j = json.loads(cli.run("search", *flags, "-o", "runs", "--json").stdout)
    out = pinmask.search(grid=8, holes="5..7", evals=300, threads=1, seed=4, top=2,
                         rerank_scenes=["letter-R"], robust="size=44um,jitter=2um")
    assert out.output is None and all(r.path is None for r in out.ranked)
    for i, m in enumerate(out.masks):
        assert j["ranked"][i]["path"] == f"runs/rank-{i + 1}.mask.json"
        assert m.to_json() == (tmp_path / j["ranked"][i]["path"]).read_text()
    got = out.to_dict()
    for k in ("used_s", "search_s", "rerank_s"):  # wall-clock seconds of each run
        assert got.pop(k) >= 0 and j.pop(k) >= 0
    j["output"] = None
    for row in j["ranked"]:
        row["path"] = None
    assert {k: v for k, v in got.items() if k not in ("masks", "log")} == j
    assert "best_per_holes" in j and "analytic_robust_mmse_psnr_db" in j["ranked"][0]
