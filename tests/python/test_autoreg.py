"""Automatic regularisation (nsr='auto', lambda_='auto'; CLI --nsr auto, --lambda auto) and the
warnings of a poor method, on captures rendered by the independent numpy model of
autoreg_scenes.py (never pinmask's simulate or PSF code); the rows of the table in
docs/decoding.md (scripts/autoreg_table.py) are recomputed and held."""
import pathlib
import re
import warnings

import numpy as np
import pytest

import autoreg_scenes as sc
import pinmask

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _decode(capture, psf, model, method, **kw):
    if method == "tv":
        kw.setdefault("nonneg", False)  # as the table (scripts/autoreg_table.py)
    return pinmask.decode(capture, psf=psf, model=model, method=method, crop="none", **kw)


@pytest.mark.parametrize("camera,method", [("phone", "wiener"), ("paper", "tikhonov"),
                                           ("lensless", "tv")])
def test_scale_invariance(camera, method):
    """x1000, electrons (3.7 per count) and counts decode to the same image times the factor."""
    model, psf = sc.cameras()[camera]
    capture, _, _ = sc.render("cell.png", model, psf, 300.0, 2.0, 5)
    key = "nsr" if method == "wiener" else "lambda_"
    kw = {key: "auto"} | ({"iters": 30} if method == "tv" else {})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the lensless capture fills the frame: not the subject
        base = _decode(capture, psf, model, method, **kw)
        for k in (1000.0, 3.7, 1.0 / 4096):
            out = _decode(capture * k, psf, model, method, **kw)
            w0, w1 = base["channels"][0]["auto_weight"], out["channels"][0]["auto_weight"]
            # TV's weight is in capture units, the closed forms' dimensionless (their search
            # ends on a flat minimum: rounding moves it by ~sqrt(machine epsilon)).
            assert w1["weight"] == pytest.approx(w0["weight"] * (k if method == "tv" else 1),
                                                 rel=1e-6)
            assert w1["noise_sigma"] == pytest.approx(w0["noise_sigma"] * k, rel=1e-9)
            img0 = np.asarray(base["image"])
            np.testing.assert_allclose(out["image"], img0 * k, rtol=0,
                                       atol=1e-6 * k * np.abs(img0).max())


def _mad_sigma(p):
    """decode/solvers/noise_estimate.hpp's rule in numpy: the MAD of the diagonal Haar details."""
    r, c = p.shape[0] // 2 * 2, p.shape[1] // 2 * 2
    q = p[:r, :c]
    d = np.abs(q[0::2, 0::2] - q[0::2, 1::2] - q[1::2, 0::2] + q[1::2, 1::2]) / 2
    return np.sort(d.ravel())[d.size // 2] / 0.6744897501960817


def _box(a, rounds):
    for _ in range(rounds):
        a = a.reshape(a.shape[0] // 2, 2, a.shape[1] // 2, 2).mean(axis=(1, 3))
    return a


@pytest.mark.parametrize("camera,rounds,normalize", [("paper", 1, "none"), ("nir-mv", 2, "l2"),
                                                     ("phone", 1, "l2")])
def test_downsampled_noise_is_measured_before_the_rounds(camera, rounds, normalize):
    """With downsample, sigma is the full-size capture's (numpy) over 2^rounds (over the window's
    L2 norm with normalize l2), and tv's weight is the rule written out in numpy on the
    downsampled capture and PSF: 2.4 sigma ||a||_2 min(1, (16 / SNR)^(2/3)), SNR = mean / sigma."""
    model, psf = sc.cameras()[camera]
    capture, _, _ = sc.render("ihc.png", model, psf, 3000.0, 2.0, 11)
    small, a = _box(capture, rounds), _box(psf, rounds)
    sigma = _mad_sigma(capture) / 2 ** rounds
    if normalize == "l2":
        sigma /= np.linalg.norm(small)
        small, a = small / np.linalg.norm(small), a / np.linalg.norm(a)
    else:
        a = a / a.sum()
    snr = small.mean() / sigma
    want = 2.4 * sigma * np.sqrt(np.sum(a ** 2)) * min(1.0, (16.0 / snr) ** (2 / 3))
    for method, kw in (("wiener", {"nsr": "auto"}), ("tv", {"lambda_": "auto", "iters": 2})):
        out = pinmask.decode(capture, psf=psf, model=model, crop="none", method=method,
                             downsample=rounds, normalize=normalize,
                             **kw)["channels"][0]["auto_weight"]
        assert out["noise_sigma"] == pytest.approx(sigma, rel=1e-12)
        if method == "tv":
            assert out["weight"] == pytest.approx(want, rel=1e-9)


def test_tv_weight_far_from_auto_warns_naming_the_keyword():
    model, psf = sc.cameras()["paper"]
    capture, _, _ = sc.render("ihc.png", model, psf, 300.0, 2.0, 6)
    auto = _decode(capture, psf, model, "tv", lambda_="auto", iters=5)
    lam = auto["channels"][0]["auto_weight"]["weight"]
    for factor in (30.0, 1 / 30.0):
        with pytest.warns(UserWarning, match=r"lambda_ .* times the automatic weight"):
            _decode(capture, psf, model, "tv", lambda_=lam * factor, iters=5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # within 10x: no warning
        _decode(capture, psf, model, "tv", lambda_=lam * 5, iters=5)
        _decode(capture, psf, model, "tv", lambda_=lam / 5, iters=5)


def test_wiener_on_a_frame_filling_linear_capture_warns_naming_tv():
    model, psf = sc.cameras()["lensless"]
    capture, _, _ = sc.render("cell.png", model, psf, 300.0, 2.0, 7)
    for method, kw in (("wiener", {"nsr": "auto"}), ("tikhonov", {"lambda_": 0.01})):
        with pytest.warns(UserWarning, match=r"fills the frame.*method tv"):
            _decode(capture, psf, model, method, **kw)
    # A small object in the middle of a dark frame: the border sees no light.
    small = np.zeros((96, 96))
    small[40:56, 40:56] = 100.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _decode(small, np.pad(np.ones((3, 3)), 2), "linear", "wiener", nsr="auto")


def test_auto_keywords_refusals():
    model, psf = sc.cameras()["paper"]
    capture, _, _ = sc.render("ihc.png", model, psf, 300.0, 2.0, 8)
    with pytest.raises(ValueError, match="nsr"):
        _decode(capture, psf, model, "wiener", nsr="automatic")
    with pytest.raises(TypeError, match="nsr"):
        _decode(capture, psf, model, "wiener", nsr=[0.1])
    with pytest.raises(ValueError, match="lambda_"):
        _decode(capture, psf, model, "wiener", lambda_="auto")
    with pytest.raises(ValueError, match="nsr_map"):
        _decode(capture, psf, model, "wiener", nsr="auto",
                nsr_map=np.full(capture.shape, 0.1))


def test_cli_auto_and_warning(cli, tmp_path):
    """The command's --nsr auto / --lambda auto: the same weight as the module, recorded in the
    stats and said by --explain; the far-weight warning is one stderr line naming the flag."""
    model, psf = sc.cameras()["paper"]
    capture, _, _ = sc.render("ihc.png", model, psf, 300.0, 2.0, 9)
    np.save(tmp_path / "cap.npy", capture)
    np.save(tmp_path / "psf.npy", psf)
    p = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--crop", "none", "--nsr", "auto",
                "--model", model, "--json", "--explain", "-o", "a.tiff")
    import json
    stats = json.loads(p.stdout)
    w = stats["channels"][0]["auto_weight"]
    mod = _decode(capture, psf, model, "wiener", nsr="auto")["channels"][0]["auto_weight"]
    # The same rule; the search ends on a flat minimum (rounding moves it by ~1e-8).
    assert w["weight"] == pytest.approx(mod["weight"], rel=1e-6)
    assert re.search(r"--nsr \S+ chosen from the capture \(noise sigma", p.stderr)
    p = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--crop", "none", "--method", "tv",
                "--model", model, "--lambda", "1e9", "--iters", "3", "-o", "b.tiff")
    lines = [l for l in p.stderr.splitlines() if "times the automatic weight" in l]
    assert len(lines) == 1 and lines[0].startswith("pinmask: warning: --lambda 1e+09")
    assert "--lambda auto" in lines[0]
    assert "must be a finite number or auto" in cli.error("decode", "cap.npy", "--psf", "psf.npy",
                                                   "--nsr", "automatic", "-o", "c.tiff")


def _table_rows():
    text = (ROOT / "docs" / "decoding.md").read_text()
    rows = []
    for line in text.splitlines():
        m = re.match(r"\| (\S+) \| (\S+\.png) \| (wiener|tv) \| (\S+) \| (\S+) \| (\S+) "
                     r"\| (\S+) \|", line)
        if m:
            rows.append((m[1], m[2], m[3], float(m[4]), float(m[5]), float(m[6]), float(m[7])))
    return rows


def test_table_rows_hold():
    """Every row of the docs table: auto within 1 dB of the oracle, and both PSNRs recomputed
    (the auto decode, and the decode at the row's oracle weight) as printed."""
    import sys
    sys.path.insert(0, str(ROOT / "scripts"))
    import autoreg_table as tab
    rows = _table_rows()
    assert len(rows) == 4 * 3 * 2
    cams = sc.cameras()
    for camera, photo, method, w_auto, p_auto, w_oracle, p_oracle in rows:
        assert p_auto >= p_oracle - 1.0, (camera, photo, method)
        model, psf = cams[camera]
        capture, truth, photons = sc.render(photo, model, psf, tab.PHOTONS, tab.READ_E, 0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            auto = tab.decode(capture, psf, model, method, "auto")
            oracle = tab.decode(capture, psf, model, method, w_oracle)
        assert auto["channels"][0]["auto_weight"]["weight"] == pytest.approx(w_auto, rel=5e-3)
        p = sc.psnr(np.asarray(auto["image"]) / photons, truth)
        assert p == pytest.approx(p_auto, abs=0.01)
        assert sc.psnr(np.asarray(oracle["image"]) / photons, truth) == pytest.approx(p_oracle,
                                                                                      abs=0.02)


def test_method_auto_chooses_tv_on_the_linear_model_and_wiener_on_the_cyclic(cli, tmp_path):
    """The default method: tv on the lensless array's capture (linear model), with
    no warning; wiener on the paper camera's period (cyclic). Both faces say so (stats, config,
    --explain, the summary; the result's method and chosen)."""
    import json
    model, psf = sc.cameras()["lensless"]
    capture, _, _ = sc.render("cell.png", model, psf, 300.0, 2.0, 7)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # tv at its automatic weight: nothing to advise
        out = pinmask.decode(capture, psf=psf, iters=20)  # iters alone: tv's parameter
        auto = pinmask.decode(capture, psf=psf)
    assert out["method"] == "tv" and out["chosen"]["method"]["reason"].startswith("iters given: only tv")
    assert auto["method"] == "tv" and "the linear model" in auto["chosen"]["method"]["reason"]
    assert auto["chosen"]["nonnegative"]["value"] == "true"
    np.save(tmp_path / "cap.npy", capture)
    np.save(tmp_path / "psf.npy", psf)
    p = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--explain", "--stats", "s.json",
                "-o", "a.npy")
    stats = json.loads((tmp_path / "s.json").read_text())
    assert stats["method"] == "tv" and stats["config"]["method"] == "auto"
    assert stats["chosen"]["method"] == {"value": "tv",
                                         "reason": auto["chosen"]["method"]["reason"]}
    assert "decode: --method tv (auto): the linear model: tv solves it" in p.stderr
    assert "method   tv (auto; linear model" in p.stdout
    np.testing.assert_array_equal(np.load(tmp_path / "a.npy"),
                                  np.asarray(auto["image"], np.float32))

    model, psf = sc.cameras()["paper"]
    capture, _, _ = sc.render("ihc.png", model, psf, 300.0, 2.0, 8)
    out = pinmask.decode(capture, psf=psf, model=model)
    assert out["method"] == "wiener"
    assert out["chosen"]["method"]["reason"].startswith("the cyclic model")


def test_cli_frame_filling_warning_names_tv_and_quiet_keeps_it_in_the_stats(cli, tmp_path):
    """Wiener given on a frame-filling linear capture: one stderr line naming --method tv; under
    --quiet no line, the stats' warnings still hold it."""
    import json
    model, psf = sc.cameras()["lensless"]
    capture, _, _ = sc.render("cell.png", model, psf, 300.0, 2.0, 7)
    np.save(tmp_path / "cap.npy", capture)
    np.save(tmp_path / "psf.npy", psf)
    p = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--method", "wiener", "-o", "w.npy")
    lines = [l for l in p.stderr.splitlines() if "fills the frame" in l]
    assert len(lines) == 1 and lines[0].startswith("pinmask: warning: wiener on the linear")
    assert lines[0].endswith("--method tv solves the linear model exactly")
    q = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--method", "wiener", "--quiet",
                "--stats", "s.json", "-o", "q.npy")
    assert "fills the frame" not in q.stderr
    assert "fills the frame" in json.loads((tmp_path / "s.json").read_text())["warnings"][0]
    # The far TV weight likewise.
    q = cli.run("decode", "cap.npy", "--psf", "psf.npy", "--method", "tv", "--lambda", "1e9",
                "--iters", "3", "--quiet", "-o", "t.npy")
    assert "times the automatic weight" not in q.stderr
