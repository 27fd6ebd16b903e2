#!/usr/bin/python3
"""The automatic-weight table of docs/decoding.md: `pinmask.decode` with nsr='auto' (wiener) and
lambda_='auto' (tv) against the oracle weight (the grid point of best PSNR against the truth),
on captures rendered by the independent numpy model of tests/python/autoreg_scenes.py (four
cameras x three photographs never used elsewhere in the tests). Run from the repository:
PYTHONPATH=build/python /usr/bin/python3 scripts/autoreg_table.py
tests/python/test_autoreg.py recomputes rows of the table and holds them."""
import pathlib
import sys
import warnings

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import autoreg_scenes as sc  # noqa: E402
import pinmask  # noqa: E402

PHOTOS = ["ihc.png", "cell.png", "microaneurysms.png"]
PHOTONS, READ_E = 400.0, 2.0  # electrons per unit scene value; read noise (electrons rms)
# The oracle's grids: 4 points per decade around the automatic weight, +-2 decades.
GRID = 10.0 ** (np.arange(-8, 9) / 4)


def decode(capture, psf, model, method, weight):
    kw = dict(psf=psf, model=model, method=method, crop="none")
    kw["nsr" if method == "wiener" else "lambda_"] = weight
    if method == "tv":
        kw["nonneg"] = False  # the table (and the TV constant's calibration) without x >= 0
    with warnings.catch_warnings():
        # The lensless captures fill the frame: wiener warns, and is in the table for that.
        warnings.simplefilter("ignore")
        return pinmask.decode(capture, **kw)


def row(camera, photo, method, seed=0):
    """(auto weight, auto PSNR, oracle weight, oracle PSNR) for one case."""
    model, psf = sc.cameras()[camera]
    capture, truth, photons = sc.render(photo, model, psf, PHOTONS, READ_E, seed)
    auto = decode(capture, psf, model, method, "auto")
    w_auto = auto["channels"][0]["auto_weight"]["weight"]
    p_auto = sc.psnr(np.asarray(auto["image"]) / photons, truth)
    scores = [(sc.psnr(np.asarray(decode(capture, psf, model, method, w_auto * g)["image"]) /
                       photons, truth), w_auto * g) for g in GRID]
    best = max(scores)
    if best in (scores[0], scores[-1]):
        raise SystemExit(f"{camera} {photo} {method}: the oracle is at the grid's end; widen GRID")
    # The weight as the table prints it (3 digits), so a test can decode at the printed value.
    w_oracle = float(f"{best[1]:.3g}")
    p_oracle = sc.psnr(np.asarray(decode(capture, psf, model, method, w_oracle)["image"]) /
                       photons, truth)
    return w_auto, p_auto, w_oracle, p_oracle


def table(methods=("wiener", "tv")):
    lines = ["| camera | photograph | method | auto weight | auto PSNR (dB) | oracle weight | "
             "oracle PSNR (dB) | auto - oracle (dB) |",
             "|---|---|---|---|---|---|---|---|"]
    for camera in sc.cameras():
        for photo in PHOTOS:
            for method in methods:
                w, p, wo, po = row(camera, photo, method)
                lines.append(f"| {camera} | {photo} | {method} | {w:.3g} | {p:.2f} | {wo:.3g} | "
                             f"{po:.2f} | {p - po:+.2f} |")
    return "\n".join(lines)


# The training set of the TV constant (decode/solvers/auto_weight.hpp kTvLambdaPerNoise): photographs and
# cameras that are not the table's.
TRAIN_PHOTOS = ["astronaut.png", "camera.png", "coffee.png"]
TRAIN_CAMERAS = {
    "paper-k12": ("cyclic", sc._camera(0.120, 0.055, 6.0, 30e-6, 16, 8, 12, 101)),
    "mv-6px": ("cyclic", sc._camera(0.025, 0.020, 0.5, 3.45e-6, 16, 6, 30, 102)),
    "wide-lens-4px": ("cyclic", sc._camera(0.050, 0.030, 1.0, 2e-6, 24, 4, 40, 103)),
    "lensless-4px": ("linear", sc._camera(1e9, 0.003, 0.4, 4e-6, 24, 4, 10, 104)),
}


def mad_sigma(p):
    """decode/solvers/noise_estimate.hpp's rule, written again in numpy."""
    r, c = p.shape[0] // 2 * 2, p.shape[1] // 2 * 2
    q = p[:r, :c]
    d = np.abs(q[0::2, 0::2] - q[0::2, 1::2] - q[1::2, 0::2] + q[1::2, 1::2]) / 2
    return np.sort(d.ravel())[d.size // 2] / 0.6744897501960817


def _tv_curve(model, psf, photo, photons, gains):
    """(SNR = mean / sigma, PSNR at lambda = g sigma ||a||_2 for each g) of one training capture."""
    capture, truth, k = sc.render(photo, model, psf, photons, READ_E, 7)
    sigma = mad_sigma(capture)
    unit = sigma * np.sqrt(np.sum(psf ** 2))
    ps = np.array([sc.psnr(np.asarray(decode(capture, psf, model, "tv", g * unit)["image"]) / k,
                           truth) for g in gains])
    return capture.mean() / sigma, ps


def calibrate_tv():
    """The TV rule's constants (decode/solvers/auto_weight.cpp). k: PSNR of TV at lambda = g sigma
    ||a||_2 for g on a grid, per low-light training case (100 and 1000 electrons per unit, every
    training camera); the g that loses least in the worst case. The fall above the knee: the
    cyclic training cameras at 1e2..1e6 electrons per unit, the loss of g = k min(1, (knee /
    SNR)^beta) per (knee, beta), against the constant k. The lensless camera is left out of the
    fall: on a frame-filling linear capture the error at high SNR is the unobserved border's, not
    the noise's, and its best gain rises with SNR instead (printed for the record)."""
    gains = 10.0 ** (np.arange(-4, 9) / 8)  # 0.32 .. 10, 8 per decade
    losses = []
    for name, (model, psf) in TRAIN_CAMERAS.items():
        for photo in TRAIN_PHOTOS:
            for photons in (100.0, 1000.0):
                _, ps = _tv_curve(model, psf, photo, photons, gains)
                losses.append(ps.max() - ps)
                print(f"{name} {photo} {photons:g}: best g {gains[ps.argmax()]:.3g} "
                      f"({ps.max():.2f} dB)", flush=True)
    for g, worst, mean in zip(gains, np.max(losses, axis=0), np.mean(losses, axis=0)):
        print(f"g {g:.4g}: worst loss {worst:.2f} dB, mean {mean:.2f}")
    gains = 10.0 ** (np.arange(-16, 9) / 8)  # 0.01 .. 10
    curves = []
    for name, (model, psf) in TRAIN_CAMERAS.items():
        for photo in TRAIN_PHOTOS:
            for photons in (1e2, 1e3, 1e4, 1e5, 1e6):
                if model == "linear" and photons > 1e5:
                    continue
                snr, ps = _tv_curve(model, psf, photo, photons, gains)
                print(f"{name} {photo} {photons:g}: SNR {snr:.1f}, best g "
                      f"{gains[ps.argmax()]:.3g} ({ps.max():.2f} dB)", flush=True)
                if model == "cyclic":
                    curves.append((snr, ps))

    def losses_of(rule):
        return [ps.max() - np.interp(np.log(rule(snr)), np.log(gains), ps) for snr, ps in curves]

    k = 2.4  # kTvLambdaPerNoise
    print(f"constant {k}: worst loss {max(losses_of(lambda s: k)):.2f} dB, "
          f"mean {np.mean(losses_of(lambda s: k)):.2f}")
    for knee in (10.0, 16.0, 25.0, 40.0):
        for beta in (0.5, 0.6, 2 / 3, 0.75):
            ls = losses_of(lambda s: k * min(1.0, (knee / s) ** beta))
            print(f"knee {knee:g}, beta {beta:.3g}: worst loss {max(ls):.2f} dB, "
                  f"mean {np.mean(ls):.2f}")


if __name__ == "__main__":
    if sys.argv[1:] == ["--calibrate-tv"]:
        calibrate_tv()
    else:
        print(table())
