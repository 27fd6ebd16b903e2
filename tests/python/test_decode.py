"""Decoding: every method and model, the CLI's numbers, a numpy deconvwnr reference, progress
and Ctrl-C, zero-copy inputs, and errors."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import pinmask

# The module and the reference do the same FFT arithmetic in a different order (FFTW vs numpy's
# pocketfft): differences are rounding, ~1e-15 relative to the image's values. 1e-10 leaves a
# wide margin yet is far below any modelling difference (a one-pixel shift or a different NSR
# changes the result by > 1e-3).
WIENER_REF_TOL = 1e-10


def deconvwnr(capture, psf, nsr):
    """MATLAB deconvwnr written in numpy: PSF zero-padded to the capture, circularly shifted so its
    centre element floor(size/2) lands at the origin, scalar NSR, real part; denominator floored
    at sqrt(eps) as MATLAB does."""
    rows, cols = capture.shape
    pad = np.zeros((rows, cols))
    pad[:psf.shape[0], :psf.shape[1]] = psf
    pad = np.roll(pad, (-(psf.shape[0] // 2), -(psf.shape[1] // 2)), axis=(0, 1))
    h = np.fft.fft2(pad)
    g = np.conj(h) / np.maximum(np.abs(h) ** 2 + nsr, np.sqrt(np.finfo(float).eps))
    return np.real(np.fft.ifft2(g * np.fft.fft2(capture)))


def test_wiener_equals_numpy_deconvwnr_one_period(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30, seed=2)["capture"]
    psf = pinmask.psf(mask7)
    # A PSF array the capture's size is read as a lensless camera's (model 'auto': linear).
    out = pinmask.decode(cap, psf=psf, method="wiener", nsr=0.01, model="cyclic")["image"]
    ref = deconvwnr(cap, psf / psf.sum(), 0.01)
    assert np.max(np.abs(out - ref)) < WIENER_REF_TOL * max(1.0, np.max(np.abs(ref)))


def test_wiener_equals_numpy_deconvwnr_small_odd_psf_padded():
    rng = np.random.default_rng(5)
    psf = rng.random((9, 7))
    cap = rng.random((40, 51))
    out = pinmask.decode(cap, psf=psf, method="wiener", nsr=0.003, crop="none")["image"]
    ref = deconvwnr(cap, psf / psf.sum(), 0.003)
    assert out.shape == (40, 51)
    assert np.max(np.abs(out - ref)) < WIENER_REF_TOL * max(1.0, np.max(np.abs(ref)))


def test_wiener_equals_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "letter-R", "--snr", "30", "--seed", "1",
            "--full-sensor", "-o", "cap.tiff")
    cli.run("decode", "cap.tiff", "--mask", "m.mask.json", "--method", "wiener", "--nsr", "0.01",
            "-o", "w.npy")
    cap, _ = pinmask.read_image(str(tmp_path / "cap.tiff"))
    out = pinmask.decode(cap, mask=str(tmp_path / "m.mask.json"), method="wiener", nsr=0.01)
    assert out["window"] == (176, 296, 128, 128)  # the centred period of 480 x 720
    assert out["period_check"]["checked"] and out["period_check"]["matches"]
    assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "w.npy"))


@pytest.mark.parametrize("method,kw", [("tikhonov", dict(lambda_=1e-3)),
                                       ("tikhonov", dict(lambda_=1e-3, regulariser="gradient")),
                                       ("tv", dict(lambda_=1e-3, iters=30)),
                                       ("tvqc", dict(noise_sigma=0.01, iters=30)),
                                       ("richardson-lucy", dict(iters=30))])
@pytest.mark.parametrize("model", ["cyclic", "linear"])
def test_every_method_equals_cli(cli, tmp_path, mask7, method, kw, model):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "letter-R", "--snr", "30", "-o", "cap.npy")
    flags = {"lambda_": "--lambda", "regulariser": "--regulariser", "iters": "--iters",
             "noise_sigma": "--noise-sigma"}
    args = [a for k, v in kw.items() for a in (flags[k], v)]
    cli.run("decode", "cap.npy", "--mask", "m.mask.json", "--method", method, "--model", model,
            *args, "-o", "x.npy")
    cap, _ = pinmask.read_image(str(tmp_path / "cap.npy"))
    out = pinmask.decode(cap, mask=mask7, method=method, model=model, **kw)
    assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "x.npy"))
    ch = out["channels"][0]
    if method in ("tv", "tvqc", "richardson-lucy"):
        assert 1 <= ch["iterations"] <= 30
        assert ch["history"].shape == (ch["iterations"], 4)


def test_progress_gets_the_iteration_and_false_stops_with_estimate(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    calls = []

    def progress(info):
        calls.append(info)
        # Stop once 5 iterations are done (or after 500 polls, so a counter that never moves
        # fails the assertions below instead of running a million iterations).
        return not (info["iteration"] >= 5 or len(calls) >= 500)

    out = pinmask.decode(cap, mask=mask7, method="tv", iters=1000000, tol=0, progress=progress,
                         poll_s=0.01)
    assert calls and out["interrupted"]
    assert calls[-1]["iteration"] >= 5
    assert all(c["max_iterations"] == 1000000 for c in calls)
    assert [c["iteration"] for c in calls] == sorted(c["iteration"] for c in calls)
    assert [c["seconds"] for c in calls] == sorted(c["seconds"] for c in calls)
    ch = out["channels"][0]
    # The solver ends after the iteration it is in: at least the iterations reported.
    assert ch["interrupted"] and calls[-1]["iteration"] <= ch["iterations"] < 1000000
    assert np.all(np.isfinite(out["image"]))


def test_progress_false_keeps_the_estimate_so_far(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]

    def progress(info):
        return False  # stop now, keep what was done

    out = pinmask.decode(cap, mask=mask7, method="richardson-lucy", iters=1000000, tol=0,
                         progress=progress, poll_s=0.01)
    assert out["interrupted"] and out["channels"][0]["iterations"] < 1000000


def test_ctrl_c_during_tv_raises_keyboard_interrupt():
    """Ctrl-C one second into a 1000-iteration TV decode is Python's KeyboardInterrupt, raised
    at once, not a result returned later."""
    rng = np.random.default_rng(2)
    cap = rng.random((768, 768))  # 1000 iterations: seconds on any machine
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.0, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pinmask.decode(cap, psf=rng.random((768, 768)), method="tv", iters=1000, tol=0,
                           crop="none")
    finally:
        timer.cancel()
    assert sent  # raised by the signal, not by anything before it


def test_progress_exception_propagates(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]

    def progress(info):
        raise LookupError("from the callback")

    with pytest.raises(LookupError, match="from the callback"):
        pinmask.decode(cap, mask=mask7, method="tv", iters=1000000, tol=0, progress=progress,
                       poll_s=0.01)


def test_rgb_and_float32_and_library_inputs(mask7):
    psf = pinmask.psf(mask7)
    cap = pinmask.simulate(mask7, "letter-R", snr_db=40)["capture"]
    assert pinmask.is_library_buffer(cap) and pinmask.is_library_buffer(psf)
    before = pinmask.input_copies()
    a = pinmask.decode(cap, psf=psf)["image"]  # both used without copies
    assert pinmask.input_copies() == before
    b = pinmask.decode(np.array(cap), psf=np.array(psf))["image"]  # copied once each
    assert pinmask.input_copies() == before + 2
    assert np.array_equal(a, b)
    c = pinmask.decode(cap.astype(np.float32), psf=psf)["image"]
    d = pinmask.decode(cap.astype(np.float32).astype(np.float64), psf=psf)["image"]
    assert np.array_equal(c, d)
    f = pinmask.decode(np.asfortranarray(cap), psf=psf)["image"]  # any order: same numbers
    assert np.array_equal(a, f)
    rgb = np.stack([cap, 2 * cap, 3 * cap], axis=2)
    # A given weight: each channel is the linear filter of its own plane.
    out = pinmask.decode(rgb, psf=psf, nsr=0.01)
    assert out["image"].shape == (128, 128, 3) and len(out["channels"]) == 3
    a_given = pinmask.decode(cap, psf=psf, nsr=0.01)["image"]
    assert np.allclose(out["image"][:, :, 2], 3 * a_given, rtol=1e-12, atol=1e-12)
    # The automatic weight (the default) is chosen per channel and does not depend on the
    # capture's scale: the search for it stops within 1e-7 of the weight, so the images agree
    # to that relative tolerance.
    auto = pinmask.decode(rgb, psf=psf)["image"]
    assert np.abs(auto[:, :, 2] - 3 * a).max() <= 1e-7 * np.abs(3 * a).max()


def test_dark_frame_subtracted(mask7):
    s = pinmask.simulate(mask7, "letter-R", photons=200, optical_density=2, dark_frame=True)
    with_dark = pinmask.decode(s["capture"], psf=s["psf"], dark=s["dark"])["image"]
    by_hand = pinmask.decode(s["capture"] - s["dark"], psf=s["psf"])["image"]
    assert np.array_equal(with_dark, by_hand)


def test_decode_errors(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    psf = pinmask.psf(mask7)
    with pytest.raises(ValueError, match="method = richardson"):
        pinmask.decode(cap, psf=psf, method="richardson")
    with pytest.raises(ValueError, match="needs the PSF"):
        pinmask.decode(cap)
    with pytest.raises(ValueError, match="needs the PSF"):
        pinmask.decode(cap, psf=psf, mask=mask7)
    bad = np.array(cap)
    bad[3, 5] = np.nan
    with pytest.raises(ValueError, match="capture"):
        pinmask.decode(bad, psf=psf)
    with pytest.raises(ValueError, match="nsr"):
        pinmask.decode(cap, psf=psf, nsr=-1)
    with pytest.raises(ValueError, match="eps|noise_sigma"):
        pinmask.decode(cap, psf=psf, method="tvqc")
    with pytest.raises(ValueError, match="2-D"):
        pinmask.decode(cap, psf=np.ones(5))
    with pytest.raises(ValueError, match="crop = middle"):
        pinmask.decode(cap, psf=psf, crop="middle")
    with pytest.raises(ValueError, match="PSF.*positive sum"):
        pinmask.decode(cap, psf=np.zeros((8, 8)))


def test_ctrl_c_during_closed_form_is_raised(mask7):
    """Nothing to keep: a Ctrl-C during a Wiener decode is a KeyboardInterrupt, as in the CLI."""
    rng = np.random.default_rng(1)
    cap = rng.random((2048, 2048))  # a decode of ~0.5 s: the poll comes first

    def progress(info):
        os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        pinmask.decode(cap, psf=rng.random((256, 256)), crop="none", method="tikhonov",
                       progress=progress, poll_s=0.0005)


def test_eps_and_noise_sigma_exclude_each_other(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    with pytest.raises(ValueError, match="eps excludes noise_sigma"):
        pinmask.decode(cap, mask=mask7, method="tvqc", eps=1.0, noise_sigma=0.01)


@pytest.mark.parametrize("method,kw,flag,users", [
    ("tv", dict(nsr=0.1), "--nsr", "wiener"),
    ("wiener", dict(lambda_=0.1), "--lambda", "tikhonov, tv"),
    ("tv", dict(regulariser="gradient"), "--regulariser", "tikhonov"),
    ("richardson-lucy", dict(eps=1.0), "--eps", "tvqc"),
    ("tv", dict(noise_sigma=1.0), "--noise-sigma", "tvqc"),
    ("tikhonov", dict(nonneg=True), "--nonneg", "tv, tvqc"),
    ("wiener", dict(iters=5), "--iters", "tv, tvqc, richardson-lucy"),
    ("tikhonov", dict(tol=0.1), "--tol", "tv, tvqc, richardson-lucy"),
])
def test_argument_the_method_ignores_is_refused_as_the_cli_does(cli, tmp_path, mask7, method, kw,
                                                                 flag, users):
    """Never silently dropped: the CLI's refusal of the flag, naming the keyword."""
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    keyword = next(iter(kw))
    with pytest.raises(ValueError, match=f"^{keyword} = .*: is not used by method {method} "
                                         f"\\(only by {users}\\)"):
        pinmask.decode(cap, mask=mask7, method=method, **kw)
    mask7.save(str(tmp_path / "m.mask.json"))
    np.save(tmp_path / "cap.npy", cap)
    value = next(iter(kw.values()))
    args = [flag] if value is True else [flag, value]
    msg = cli.error("decode", "cap.npy", "--mask", "m.mask.json", "--method", method, *args,
                    "-o", "x.npy")
    assert f"is not used by --method {method} (only by {users})" in msg


def test_preprocessing_arguments_equal_cli(cli, tmp_path, mask7):
    """background, downsample, normalize, precision, threads: the CLI's flags, the same bytes."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "letter-R", "--snr", "30", "--seed", "3",
            "--full-sensor", "-o", "cap.npy")
    cap = np.load(tmp_path / "cap.npy")
    for kw, flags in [
        (dict(background=0.01), ["--background", "0.01"]),
        (dict(downsample=1), ["--downsample", "1"]),
        (dict(normalize="l2"), ["--normalize", "l2"]),
        (dict(precision="single", threads=1), ["--precision", "single", "--threads", "1"]),
        (dict(background="none", downsample=1, normalize="l2", precision="double", threads=2),
         ["--background", "none", "--downsample", "1", "--normalize", "l2", "--precision",
          "double", "--threads", "2"]),
    ]:
        cli.run("decode", "cap.npy", "--mask", "m.mask.json", *flags, "-o", "x.npy")
        out = pinmask.decode(cap, mask=mask7, **kw)
        assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "x.npy")), kw


def test_downsample_halves_the_window_and_precision_changes_rounding_only(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30, full_sensor=True)["capture"]
    full = pinmask.decode(cap, mask=mask7)
    half = pinmask.decode(cap, mask=mask7, downsample=1)
    assert half["window"][2:] == (full["window"][2] // 2, full["window"][3] // 2)
    d = pinmask.decode(cap, mask=mask7, precision="double")["image"]
    s = pinmask.decode(cap, mask=mask7, precision="single")["image"]
    assert not np.array_equal(d, s)  # single really ran in float32
    assert np.linalg.norm(s - d) <= 1e-4 * np.linalg.norm(d)  # rounding of float32 transforms


def test_background_corner_equals_cli_and_needs_a_measured_psf(cli, tmp_path, mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30, full_sensor=True)["capture"]
    with pytest.raises(ValueError, match="needs a measured PSF"):
        pinmask.decode(cap, mask=mask7, background="corner")
    # A measured PSF: the mask's, with a 20 px border, on a flat camera background of 0.5
    # counts (the corner patch, rows/cols 5..14, lies in the border: exactly 0.5).
    psf = np.pad(np.array(pinmask.psf(mask7)), 20) + 0.5
    np.save(tmp_path / "psf.npy", psf)
    np.save(tmp_path / "cap.npy", cap + 0.5)
    cli.run("decode", "cap.npy", "--psf", "psf.npy", "--background", "corner", "-o", "x.npy")
    out = pinmask.decode(cap + 0.5, psf=psf, background="corner")
    assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "x.npy"))


@pytest.mark.parametrize("kw,pattern", [
    (dict(normalize="l1"), "^normalize = l1"),
    (dict(precision="half"), "^precision = half"),
    (dict(threads=-1), "^threads = -1"),
    (dict(threads=5000), "^threads = 5000"),
    (dict(downsample=13), "downsample"),
    (dict(downsample=-1), "downsample"),
    (dict(background="sky"), "^background = 'sky'"),
    (dict(background=float("nan")), "background"),
    (dict(background=True), "^background = True"),
    (dict(background=1e300), "background"),
])
def test_bad_preprocessing_arguments_are_value_errors(mask7, kw, pattern):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    with pytest.raises(ValueError, match=pattern):
        pinmask.decode(cap, mask=mask7, **kw)


def test_progress_follows_the_method_auto_chooses():
    """method='auto' resolves inside the pipeline (tv here: a PSF that covers a capture lit to
    its edges, the linear model); progress and stopping follow that method: max_iterations is
    tv's 200, and returning False stops it with the estimate so far."""
    rng = np.random.default_rng(3)
    cap = 1.0 + rng.random((256, 256))
    psf = rng.random((256, 256))
    calls = []

    def progress(info):
        calls.append(info)
        return False

    out = pinmask.decode(cap, psf=psf, progress=progress, poll_s=0.001)
    assert out["method"] == "tv" and out["chosen"]["method"]["value"] == "tv"
    assert calls and all(c["max_iterations"] == 200 for c in calls)
    assert out["interrupted"] and out["channels"][0]["iterations"] < 200
    # A closed form chosen the same way reports no iterations.
    calls.clear()
    period = np.zeros((32, 32))
    period[3, 5] = period[17, 20] = 1.0  # a PSF smaller than the capture: cyclic, wiener
    out = pinmask.decode(cap, psf=period, progress=progress, poll_s=0.001)
    assert out["method"] == "wiener"
    assert all(c["max_iterations"] == 0 for c in calls)
