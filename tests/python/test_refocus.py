"""Refocus at a pitch that is not a whole number of pixels (the NIR camera of docs/fabrication.md
at 2 m: 32.83 px per cell). `decode --mask M --object-distance 2m` must decode within 0.5 dB of
decoding with the true PSF and the linear model. The capture and the true PSF are rendered here
with numpy, independently of pinmask's forward code: every pinhole's box spot at its Eq. (3)
position (q = (1 - f/f' + f/u) s) by exact pixel overlap, and a linear convolution by FFT over a
grid larger than capture + PSF (the PSF's centre element floor(size/2) at the origin).
Also the phone-like camera refocused at 0.6 m on a scene that fills the frame: the default decode
(method auto: tv there) within 1 dB of tv at the oracle weight (docs/decoding.md).
"""
import json
import warnings

import numpy as np
import pytest

F, FL, W = 0.045, 0.075, 5.86e-6
NIR = ["--pixel-pitch", "5.86um", "--sensor", "1920x1200", "--lens-focal", "75mm",
       "--sensor-distance", "45mm", "--object-distance", "1.2m", "--wavelength", "850nm"]
ROWS, COLS = 1200, 1920
U = 2.0
NSR = "1e-4"


def box_overlap(centre, side, size):
    """Overlap of [centre - side/2, centre + side/2] with each pixel [k, k + 1)."""
    k = np.arange(size, dtype=float)
    return np.clip(np.minimum(k + 1, centre + side / 2) - np.maximum(k, centre - side / 2), 0, None)


def true_psf(mask, u):
    pattern = mask["pattern"]
    n = pattern["n"]
    tiles_r, tiles_c = pattern["tiles"]
    d = mask["optics"]["pinhole_m"]
    pitch = d * (1 - F / FL + F / u) / W  # px per cell at u
    holes = pattern["pinholes"]
    psf = np.zeros((ROWS, COLS))
    for ti in range(tiles_r):
        for tj in range(tiles_c):
            for r, c in holes:
                cy = ROWS / 2 + (ti * n + r + 0.5 - n * tiles_r / 2) * pitch
                cx = COLS / 2 + (tj * n + c + 0.5 - n * tiles_c / 2) * pitch
                psf += np.outer(box_overlap(cy, pitch, ROWS), box_overlap(cx, pitch, COLS))
    return psf / (pitch * pitch * len(holes)), pitch


def scene(shape, rng):
    """A smooth random texture in [0, 1]: white noise low-passed in the Fourier domain."""
    fy = np.fft.fftfreq(shape[0])[:, None]
    fx = np.fft.rfftfreq(shape[1])[None, :]
    spectrum = np.fft.rfft2(rng.standard_normal(shape)) * np.exp(-(fy**2 + fx**2) / (2 * 0.03**2))
    x = np.fft.irfft2(spectrum, shape)
    return (x - x.min()) / (x.max() - x.min())


def capture_of(x, psf):
    """Linear convolution, cropped to the centred capture window (x's grid >= capture + psf)."""
    g = x.shape
    pad = np.zeros(g)
    pad[:psf.shape[0], :psf.shape[1]] = psf
    pad = np.roll(pad, (-(psf.shape[0] // 2), -(psf.shape[1] // 2)), axis=(0, 1))
    y = np.fft.irfft2(np.fft.rfft2(x) * np.fft.rfft2(pad), g)
    r0, c0 = (g[0] - ROWS) // 2, (g[1] - COLS) // 2
    return y[r0:r0 + ROWS, c0:c0 + COLS], (r0, c0)


def psnr_aligned(estimate, truth):
    """PSNR after the least-squares gain and offset (the decoders' scale is their own)."""
    a = np.stack([estimate.ravel(), np.ones(estimate.size)], axis=1)
    coef, *_ = np.linalg.lstsq(a, truth.ravel(), rcond=None)
    err = a @ coef - truth.ravel()
    return 10 * np.log10(1.0 / np.mean(err**2))


def test_refocus_at_2m_within_half_a_db_of_the_true_psf(cli, tmp_path):
    cli.run("design", *NIR, "--pixels-per-cell", "34", "--save-camera", "cam.camera.json")
    cli.run("generate", "--camera", "cam.camera.json", "--kernel", "box", "--seed", "4",
            "-o", "m.mask.json")
    mask = json.loads((tmp_path / "m.mask.json").read_text())
    psf, pitch = true_psf(mask, U)
    assert abs(pitch - round(pitch)) * 16 > 1  # not a whole number: 32.83 px per cell
    rng = np.random.default_rng(11)
    # An object on a dark background whose whole image lands on the sensor (the PSF spans about
    # 1050 px): the linear model's zero padding is then what the camera saw.
    grid = (2 * ROWS, 2 * COLS)
    r0, c0 = (grid[0] - ROWS) // 2, (grid[1] - COLS) // 2
    inner = (slice(540, 660), slice(660, 1260))  # the object, in frame coordinates
    x = np.zeros(grid)
    x[r0 + 540:r0 + 660, c0 + 660:c0 + 1260] = scene((120, 600), rng)
    capture, (cr, cc) = capture_of(x, psf)
    assert (cr, cc) == (r0, c0)
    capture = capture + rng.normal(0, capture.max() * 10 ** (-60 / 20), capture.shape)  # 60 dB
    np.save(tmp_path / "capture.npy", capture.astype(np.float32))
    np.save(tmp_path / "true-psf.npy", psf.astype(np.float32))

    cli.run("decode", "capture.npy", "--mask", "m.mask.json", "--object-distance", "2m",
            "--nsr", NSR, "--stats", "refocus.json", "-o", "refocus.npy")
    cli.run("decode", "capture.npy", "--psf", "true-psf.npy", "--model", "linear", "--crop",
            "none", "--nsr", NSR, "-o", "true.npy")
    stats = json.loads((tmp_path / "refocus.json").read_text())
    assert stats["psf"]["refocus"]["geometry"] == "exact"
    assert abs(stats["psf"]["refocus"]["pitch_px"] - pitch) < 1e-9
    assert stats["config"]["model"] == "linear"

    truth = x[r0:r0 + ROWS, c0:c0 + COLS][inner]
    refocus_est = np.load(tmp_path / "refocus.npy")[inner]
    true_est = np.load(tmp_path / "true.npy")[inner]
    refocus = psnr_aligned(refocus_est, truth)
    true = psnr_aligned(true_est, truth)
    print(f"refocus {refocus:.2f} dB, true PSF {true:.2f} dB")
    assert refocus >= true - 0.5, (refocus, true)
    # The module refocuses the same way, to the same numbers (decode(mask=, object_distance=)).
    import pinmask
    out = pinmask.decode(np.load(tmp_path / "capture.npy"), mask=str(tmp_path / "m.mask.json"),
                         object_distance="2m", nsr=float(NSR))
    assert out["refocus"] == stats["psf"]["refocus"]
    assert np.array_equal(out["image"].astype(np.float32), np.load(tmp_path / "refocus.npy"))
    # The decode itself works on this capture: the estimate follows the object.
    assert np.corrcoef(true_est.ravel(), truth.ravel())[0, 1] > 0.5
    assert np.corrcoef(refocus_est.ravel(), truth.ravel())[0, 1] > 0.5


# The phone-like camera of docs/decoding.md ("Refocus on a frame-filling scene"): 1.12 um pixels,
# f' = 4.4 mm, sensor at 4.2 mm, 530 nm, designed for 0.3 m (scripts/refocus_phone.py measures
# the full-size figure with these functions).
PHONE_F, PHONE_FL, PHONE_W = 4.2e-3, 4.4e-3, 1.12e-6


def phone_flags(rows, cols):
    return ["--pixel-pitch", "1.12um", "--sensor", f"{cols}x{rows}", "--lens-focal", "4.4mm",
            "--sensor-distance", "4.2mm", "--object-distance", "0.3m", "--wavelength", "530nm"]


def phone_psf(mask, u, rows, cols):
    """Every pinhole's box spot at its Eq. (3) position at u by exact pixel overlap, unit sum."""
    p = mask["pattern"]
    n, (tr, tc) = p["n"], p["tiles"]
    pitch = mask["optics"]["pinhole_m"] * (1 - PHONE_F / PHONE_FL + PHONE_F / u) / PHONE_W
    psf = np.zeros((rows, cols))
    for ti in range(tr):
        for tj in range(tc):
            for r, c in p["pinholes"]:
                cy = rows / 2 + (ti * n + r + 0.5 - n * tr / 2) * pitch
                cx = cols / 2 + (tj * n + c + 0.5 - n * tc / 2) * pitch
                psf += np.outer(box_overlap(cy, pitch, rows), box_overlap(cx, pitch, cols))
    return psf / psf.sum()


def fractal_scene(shape, rng):
    """A 1/f texture in [0, 1] (a natural scene's spectrum), filling the whole grid."""
    fy = np.fft.fftfreq(shape[0])[:, None]
    fx = np.fft.rfftfreq(shape[1])[None, :]
    s = np.fft.rfft2(rng.standard_normal(shape)) / np.maximum(np.hypot(fy, fx), 1.0 / max(shape))
    x = np.fft.irfft2(s, shape)
    return (x - x.min()) / (x.max() - x.min())


def phone_capture(mask, u, rows, cols, peak, seed):
    """A frame-filling capture of the phone camera at u: a 1/f scene over a grid twice the
    sensor, linear convolution by FFT, the centred sensor window, Poisson photons (`peak`
    electrons at the brightest pixel) and 2 e- read noise. Returns (capture, scene window)."""
    rng = np.random.default_rng(seed)
    psf = phone_psf(mask, u, rows, cols)
    grid = (2 * rows, 2 * cols)
    x = fractal_scene(grid, rng)
    pad = np.zeros(grid)
    pad[:rows, :cols] = psf
    pad = np.roll(pad, (-(rows // 2), -(cols // 2)), (0, 1))
    y = np.fft.irfft2(np.fft.rfft2(x) * np.fft.rfft2(pad), grid)
    r0, c0 = (grid[0] - rows) // 2, (grid[1] - cols) // 2
    cap = y[r0:r0 + rows, c0:c0 + cols]
    cap = rng.poisson(np.maximum(cap / cap.max() * peak, 0)) + rng.normal(0, 2, cap.shape)
    return cap, x[r0:r0 + rows, c0:c0 + cols]


def test_refocus_on_a_frame_filling_scene_default_within_1db_of_oracle_tv(cli, tmp_path):
    """The phone camera refocused at 0.6 m on a scene that fills the frame (a 252 x 189 window
    of its sensor): `decode --mask M --object-distance 0.6m` with its defaults chooses tv (the
    linear model, the frame filled) and lands within 1 dB of tv at the weight the truth chooses;
    Wiener, the closed form the default was before, is further off."""
    rows, cols, u = 189, 252, 0.6
    cli.run("design", *phone_flags(rows, cols), "--save-camera", "cam.camera.json")
    cli.run("generate", "--camera", "cam.camera.json", "--seed", "4", "-o", "m.mask.json")
    mask = json.loads((tmp_path / "m.mask.json").read_text())
    cap, scene = phone_capture(mask, u, rows, cols, 2000.0, 5)
    np.save(tmp_path / "cap.npy", cap.astype(np.float32))
    p = cli.run("decode", "cap.npy", "--mask", "m.mask.json", "--object-distance", "0.6m",
                "--stats", "s.json", "--explain", "-o", "x.npy")
    stats = json.loads((tmp_path / "s.json").read_text())
    assert stats["method"] == "tv" and stats["config"]["method"] == "auto"
    assert stats["chosen"]["method"]["value"] == "tv"
    assert stats["chosen"]["method"]["reason"].startswith("the linear model")
    assert stats["config"]["chosen"] == stats["chosen"]
    assert "--method tv (auto): the linear model: tv solves it" in p.stderr
    assert "warning" not in p.stderr
    default = np.load(tmp_path / "x.npy")
    # The module chooses the same, to the same numbers.
    import pinmask
    cap32 = np.load(tmp_path / "cap.npy")
    out = pinmask.decode(cap32, mask=str(tmp_path / "m.mask.json"), object_distance="0.6m")
    assert out["method"] == "tv" and out["chosen"]["method"]["value"] == "tv"
    assert np.array_equal(out["image"].astype(np.float32), default)

    inner = (slice(8, rows - 8), slice(8, cols - 8))
    truth = scene[inner]

    def quality(image):
        return psnr_aligned(np.asarray(image)[inner], truth)

    def decode(**kw):
        return pinmask.decode(cap32, mask=str(tmp_path / "m.mask.json"), object_distance="0.6m",
                              **kw)["image"]

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the grid's ends are far from the automatic weight
        oracle = {lam: quality(decode(method="tv", lambda_=lam * cap.max()))
                  for lam in (1e-4, 3e-4, 1e-3, 3e-3, 1e-2)}
    with pytest.warns(UserWarning, match="fills the frame"):
        wiener = quality(decode(method="wiener"))
    best = max(oracle.values())
    print(f"default {quality(default):.2f} dB, wiener {wiener:.2f} dB, oracle tv {best:.2f} dB")
    assert quality(default) >= best - 1.0, (quality(default), oracle)
    assert wiener < quality(default)
