"""Each capability's Python result is its command's --json: one library transaction, one io/
rendering, so `result.to_dict()` equals what the command prints for the same settings (the
library's words that name a setting are in each face's own spelling)."""
import json

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
