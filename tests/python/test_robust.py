"""Fabrication robustness (--robust) in the module: metrics() and search() against the CLI."""
import json

import pytest

import pinmask

ERRORS = "size=44um,jitter=2um"


def test_metrics_robust_equals_cli_score(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    s = json.loads(cli.run("score", "m.mask.json", "--snr", "40", "--nsr", "tuned", "--metrics",
                           "analytic", "--robust", ERRORS, "--json").stdout)["masks"][0]
    row = pinmask.metrics(str(tmp_path / "m.mask.json"), snr_db=40, tv_iterations=20,
                          robust=ERRORS)
    # The same closed form, prior and filter: the same numbers, to the last bit.
    assert row["analytic_robust_wiener_psnr_db_snr40"] == s["analytic_robust_wiener_psnr_db_snr40"]
    assert row["analytic_robust_wiener_loss_db_snr40"] == s["analytic_robust_wiener_loss_db_snr40"]
    assert row["analytic_robust_wiener_psnr_db"] == s["analytic_robust_wiener_psnr_db_snr40"]
    assert row["analytic_wiener_psnr_db_snr40"] == s["analytic_wiener_psnr_db_snr40"]
    # The errors cost PSNR, and the loss is nominal minus robust.
    assert 0 < row["analytic_robust_wiener_loss_db_snr40"] < 5
    assert row["analytic_robust_wiener_loss_db_snr40"] == pytest.approx(
        row["analytic_wiener_psnr_db_snr40"] - row["analytic_robust_wiener_psnr_db_snr40"],
        abs=1e-9)
    # Without robust no robust key (as score without --robust).
    plain = pinmask.metrics(mask7, snr_db=40, tv_iterations=20)
    assert not any(k.startswith("robust") for k in plain)


def test_metrics_robust_bad_values_same_message_as_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    for bad in ["size=-1um", "jitter=nan", "missing=1", "size=5um,size=6um", "color=3",
                "size"]:
        msg = cli.error("score", "m.mask.json", "--metrics", "analytic", "--robust", bad)
        with pytest.raises(ValueError) as e:
            pinmask.metrics(mask7, tv_iterations=20, robust=bad)
        # The same words, the setting spelled as the keyword instead of the flag.
        assert "--robust" in msg
        assert str(e.value) == msg.replace("--robust", "robust"), bad


def test_search_robust_objective_same_masks_as_cli(cli, tmp_path):
    cli.run("search", "--preset", "paper", "--grid", "16", "--holes", "20", "--evals", "300",
            "--threads", "1", "--seed", "5", "--top", "2", "--no-rerank", "--robust", ERRORS,
            "--objective", "robust", "-o", "runs")
    r = pinmask.search(grid=16, holes=20, evals=300, threads=1, seed=5, top=2, rerank_scenes=[],
                       robust=ERRORS, objective="robust")
    assert len(r["ranked"]) == 2
    for i, (c, m) in enumerate(zip(r["ranked"], r["masks"])):
        assert m.to_json() == (tmp_path / "runs" / f"rank-{i + 1}.mask.json").read_text()
        t = c  # every term is a key of the ranked row
        # The robust objective: -robust PSNR; the nominal figure beside it is higher.
        assert c["objective"] == pytest.approx(-t["analytic_robust_mmse_psnr_db"], abs=1e-12)
        assert t["analytic_mmse_psnr_db"] > t["analytic_robust_mmse_psnr_db"]
    with pytest.raises(ValueError, match="^objective = robust: needs robust with"):
        pinmask.search(evals=10, objective="robust")  # needs robust errors
    with pytest.raises(ValueError, match="^objective = best"):
        pinmask.search(evals=10, objective="best", robust=ERRORS)


def test_decode_nsr_map_equals_cli(cli, tmp_path):
    """decode(nsr_map=) is `decode --nsr-map`: the robust decoder's files from score, the same
    estimate as the command's (its .npy output is float32: compared after the same rounding),
    and not the scalar-NSR estimate; misuse raises the CLI's refusals as ValueError."""
    np = pytest.importorskip("numpy")
    mask = pinmask.generate(family="random", holes=20, seed=3)
    mask.save(str(tmp_path / "m.mask.json"))
    cli.run("score", "m.mask.json", "--snr", "50", "--metrics", "analytic", "--robust", ERRORS,
            "--robust-decoder", "dec")
    sim = pinmask.simulate(mask, snr_db=50, seed=4)
    capture = np.asarray(sim["capture"], dtype=np.float64)
    np.save(tmp_path / "c.npy", capture)
    cli.run("decode", "c.npy", "--psf", "dec/robust-psf.npy", "--nsr-map", "dec/robust-nsr.npy",
            "--crop", "none", "-o", "x.npy")
    psf = np.load(tmp_path / "dec" / "robust-psf.npy")
    nsr = np.load(tmp_path / "dec" / "robust-nsr.npy")
    # The robust PSF is one period of the mask: the command knows it from the file's sidecar,
    # an array does not (model 'auto' would read a PSF the capture's size as a lensless camera's).
    out = pinmask.decode(capture, psf=psf, nsr_map=nsr, crop="none", model="cyclic")
    assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "x.npy"))
    scalar = pinmask.decode(capture, psf=psf, crop="none", model="cyclic")
    assert not np.allclose(scalar["image"], out["image"])
    with pytest.raises(ValueError, match="nsr_map"):
        pinmask.decode(capture, psf=psf, nsr_map=nsr, nsr=0.01, crop="none")
    with pytest.raises(ValueError, match="wiener"):
        pinmask.decode(capture, psf=psf, nsr_map=nsr, method="tv", crop="none")
    with pytest.raises(ValueError, match="nsr_map = 127 x 128: must have the working size"):
        pinmask.decode(capture, psf=psf, nsr_map=nsr[:-1], crop="none", model="cyclic")
    with pytest.raises(ValueError):
        pinmask.decode(capture, psf=psf, nsr_map=-nsr, crop="none")


def test_compare_robust_equals_cli(cli, tmp_path, mask7):
    """compare(robust=) as `compare --robust`: every row's robust figure is the command's, and
    the same as metrics(robust=) for that mask (one library path)."""
    mask7.save(str(tmp_path / "m.mask.json"))
    pinmask.generate(seed=8).save(str(tmp_path / "o.mask.json"))
    spec = "size=44um,jitter=2um"
    j = json.loads(cli.run("compare", "m.mask.json", "o.mask.json", "--robust", spec,
                           "--tv-iters", "10", "--json").stdout)
    out = pinmask.compare([str(tmp_path / "m.mask.json"), str(tmp_path / "o.mask.json")],
                          robust=spec, tv_iterations=10)
    assert len(out["masks"]) == 2
    for row, cli_row in zip(out["masks"], j["masks"]):
        for key in ["analytic_robust_wiener_psnr_db_snr30", "analytic_robust_wiener_loss_db_snr30"]:
            assert row[key] == cli_row[key], key
        assert row["analytic_robust_wiener_loss_db_snr30"] > 0  # the errors cost
    single = pinmask.metrics(str(tmp_path / "m.mask.json"), robust=spec, tv_iterations=10)
    assert single["analytic_robust_wiener_psnr_db"] == \
        out["masks"][0]["analytic_robust_wiener_psnr_db_snr30"]
