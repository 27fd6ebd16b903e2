#!/usr/bin/python3
"""The real-capture defaults table of docs/decoding.md: the DiffuserCam hand and USAF target
(tests/python/real_captures.py) decoded by `pinmask.decode` given only the capture and the PSF
(and the method), against the best decode a sweep over the settings finds. Quality is the PSNR
after gain and offset against a reference written in numpy (the source's preprocessing and
non-negative FISTA on the linear model, 300 iterations: the data README's clean hand), so no
decode is judged by pinmask's own code. Run from the repository:
PINMASK_SHARED_DIR=/work/shared PYTHONPATH=build/python /usr/bin/python3 scripts/real_defaults_table.py
(--nonneg: the non-negativity figures of docs/decoding.md instead; --auto: the default decode,
its method chosen from the capture, against the best of both methods' sweeps; --noise: the noise
sigma after each round of averaging and before it).
tests/python/test_real_defaults.py recomputes the rows at a smaller size and holds them."""
import itertools
import pathlib
import sys
import warnings

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import real_captures as rc  # noqa: E402
import pinmask  # noqa: E402

# Rounds of 2 x 2 averaging: the hand at the ADMM notebook's 300 x 400, the USAF target as it is.
ROUNDS = {"hand": 2, "usaf": 0}
# The sweep: each method's weight on a grid around the automatic one (x 10^(i/4), +-2 decades
# for wiener; x 10^(i/2), +-1.5 decades for tv), over the model, the source's background or
# none, and for tv normalisation and non-negativity.
WIENER_GRID = 10.0 ** (np.arange(-8, 9) / 4)
TV_GRID = 10.0 ** (np.arange(-3, 4) / 2)


def source_background(name):
    return "corner" if rc.CAPTURES[name][2] == "corner" else 100.0


def decode(cap, psf, rounds, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pinmask.decode(cap, psf=psf, downsample=rounds, **kw)


def score(result, reference):
    return rc.psnr_fit(np.asarray(result["image"], float).squeeze(), reference)


def weight_of(result):
    return result["channels"][0]["auto_weight"]["weight"]


def sweep(name, method, cap, psf, rounds, reference, quick=False):
    """(best PSNR, its settings) over the grid of `method` (quick, for the test: the source's
    background only, and tv's weight at 3 points a half decade apart with x >= 0 and the l2
    normalisation only, where the full sweep finds tv's best)."""
    best = (-np.inf, None)
    key = "nsr" if method == "wiener" else "lambda_"
    models = ["cyclic", "linear"] if method == "wiener" else ["linear"]
    norms = ["none"] if method == "wiener" else (["l2"] if quick else ["none", "l2"])
    nonnegs = [None] if method == "wiener" else ([True] if quick else [True, False])
    grid = WIENER_GRID if method == "wiener" else (TV_GRID[2:5] if quick else TV_GRID)
    backgrounds = [source_background(name)] if quick else ["none", source_background(name)]
    for model, bg, norm, nn in itertools.product(models, backgrounds, norms, nonnegs):
        kw = dict(method=method, model=model, background=bg, normalize=norm)
        if nn is not None:
            kw["nonneg"] = nn
        w0 = weight_of(decode(cap, psf, rounds, **kw, **{key: "auto"}, **(
            {"iters": 1} if method == "tv" else {})))
        for g in grid:
            p = score(decode(cap, psf, rounds, **kw, **{key: w0 * g}), reference)
            if p > best[0]:
                best = (p, dict(kw, **{key: float(f"{w0 * g:.3g}")}))
    return best


def rows(names=("hand", "usaf"), methods=("wiener", "tv"), rounds=None, iters=300, quick=False):
    out = []
    for name in names:
        k = (rounds or ROUNDS)[name]
        cap, psf = rc.load(name)
        reference = rc.fista_nonneg(*rc.preprocess(name, k), iters=iters)
        for method in methods:
            default = decode(cap, psf, k, method=method)
            p_default = score(default, reference)
            p_best, settings = sweep(name, method, cap, psf, k, reference, quick)
            out.append((name, method, default["chosen"], weight_of(default), p_default, p_best,
                        settings))
    return out


def table():
    lines = ["| capture | method | chosen (model, crop, background, nonneg) | auto weight | "
             "default PSNR (dB) | best settings | best PSNR (dB) | default - best (dB) |",
             "|---|---|---|---|---|---|---|---|"]
    for name, method, chosen, w, p, pb, s in rows():
        c = ", ".join(chosen[k]["value"] for k in ("model", "crop", "background", "nonnegative")
                      if k in chosen)
        sw = ", ".join(f"{k} {v}" for k, v in s.items() if k != "method")
        lines.append(f"| {name} | {method} | {c} | {w:.3g} | {p:.2f} | {sw} | {pb:.2f} | "
                     f"{p - pb:+.2f} |")
    return "\n".join(lines)


def auto_rows(rounds=None, iters=300):
    """The default decode (method auto: the method chosen from the capture too) against the
    best of the wiener and tv sweeps. Lines of (capture, method chosen, its reason, default
    PSNR, best PSNR, best settings)."""
    out = []
    for name in ("hand", "usaf"):
        k = (rounds or ROUNDS)[name]
        cap, psf = rc.load(name)
        reference = rc.fista_nonneg(*rc.preprocess(name, k), iters=iters)
        default = decode(cap, psf, k)
        best = max(sweep(name, m, cap, psf, k, reference) for m in ("wiener", "tv"))
        out.append((name, default["method"], default["chosen"]["method"]["reason"],
                    score(default, reference), best[0], best[1]))
    return out


def nonneg_rows():
    """tv at its automatic weight with x >= 0 and without: the real captures (hand 150 x 200,
    USAF 135 x 160) against the reference, per normalisation; captures rendered by
    tests/python/autoreg_scenes.py (400 electrons per unit, 2 e- read noise, seed 0) against
    the truth. Lines of (case, PSNR with x >= 0, PSNR without)."""
    import autoreg_scenes as sc
    out = []
    for name, k in (("hand", 3), ("usaf", 1)):
        cap, psf = rc.load(name)
        reference = rc.fista_nonneg(*rc.preprocess(name, k))
        for norm in ("none", "l2"):
            out.append((f"{name} normalize {norm}",) + tuple(
                score(decode(cap, psf, k, method="tv", normalize=norm, nonneg=nn), reference)
                for nn in (True, False)))
    for camera in ("paper", "phone", "lensless"):
        model, psf = sc.cameras()[camera]
        for photo in ("ihc.png", "cell.png"):
            cap, truth, photons = sc.render(photo, model, psf, 400.0, 2.0, 0)
            out.append((f"{camera} {photo}",) + tuple(
                sc.psnr(np.asarray(pinmask.decode(cap, psf=psf, model=model, crop="none",
                                                  method="tv", nonneg=nn)["image"]) / photons,
                        truth) for nn in (True, False)))
    return out


def noise_rows():
    """Per capture and rounds of 2 x 2 averaging: the noise sigma the MAD rule of
    decode/solvers/noise_estimate.hpp reads after the rounds (numpy), the full-size one over
    2^rounds, the sigma pinmask records for its default decode (a background taken off does not
    move it) and the SNR of the TV rule, the capture's mean over that sigma."""
    import autoreg_table as at
    out = []
    for name in ("hand", "usaf"):
        cap, psf = rc.load(name)
        full = at.mad_sigma(cap)
        for k in range(4):
            recorded = decode(cap, psf, k)["channels"][0]["auto_weight"]["noise_sigma"]
            out.append((name, k, at.mad_sigma(rc.box_downsample(cap, k)), full / 2 ** k,
                        recorded, cap.mean() / recorded))
    return out


if __name__ == "__main__":
    if not rc.available():
        raise SystemExit(f"no real captures under {rc.real_dir()} (set PINMASK_SHARED_DIR)")
    if sys.argv[1:] == ["--auto"]:
        for name, method, reason, p, pb, settings in auto_rows():
            print(f"{name}: default chooses {method} ({reason}): {p:.2f} dB; best {pb:.2f} dB "
                  f"({settings}): default - best {p - pb:+.2f} dB")
    elif sys.argv[1:] == ["--noise"]:
        for name, k, after, before, recorded, snr in noise_rows():
            print(f"{name} {k} rounds: sigma after the rounds {after:.1f}, full size / 2^k "
                  f"{before:.1f}, recorded {recorded:.1f}; SNR (mean / recorded) {snr:.0f}")
    elif sys.argv[1:] == ["--nonneg"]:
        for case, a, b in nonneg_rows():
            print(f"{case}: x >= 0 {a:.2f} dB, free {b:.2f} dB")
    else:
        print(table())
