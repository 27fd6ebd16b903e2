"""The linear model's comparison of scripts/bench-peers: pinmask's TV against LenslessPiCam's own
ADMM (its lensless/recon/admm.py, imported from a checkout given by the caller, never copied
here), on three simulated lensless captures with a ground truth.

Problems (each capture rendered here by scipy's fftconvolve, mode "valid", from a scene larger
than the sensor by the PSF's extent: neither decoder's model renders it):
- "diffusercam": the DiffuserCam tutorial PSF (../shared/data/real), its corner background
  removed, 4x box-downsampled to 300 x 400; skimage's "coffee" photograph; 40 dB SNR.
- "pinhole array": the paper camera's mask, exact-geometry PSF over the whole 480 x 720 sensor
  (pinmask.psf(geometry="exact")), 2 x 2 binned to 240 x 360; skimage's "motorcycle_left"
  photograph; 40 dB.
- "lensless pinhole array": a lensless camera (no lens, sensor 20 mm behind the mask, 5 um
  pixels, object at 2 m) with a random 10 x 10 pattern of 15 pinholes, exact-geometry PSF over a
  320 x 400 sensor, 2 x 2 binned to 160 x 200; skimage's "chelsea" photograph; 40 dB.
(The binning keeps each ADMM tau sweep within minutes on a shared 2-core machine.)
The PSF handed to both decoders is sensor-sized (LenslessPiCam's ADMM needs the PSF and the data
of one shape); each decoder normalises as it does by itself: LenslessPiCam's load_data divides the
PSF by its L2 norm and the data by its maximum (done here the same way), pinmask gets the PSF
summing to 1 and the capture as rendered.

Rule (the same for both): each decoder's weight (LenslessPiCam: tau; pinmask: lambda, relative to
the capture's peak) is tuned on a grid, picking the weight whose best PSNR over the iterations is
highest; that best PSNR is the oracle stop, and the time to it the process CPU time (one thread:
torch.set_num_threads(1), FFTW one thread) from the call that builds the decoder to that iterate.
The ADMM is stepped by its own _update and read after every iteration (a copy of its estimate,
cropped and clipped as its _form_image does, without _form_image's in-place clipping, which would
change the iteration); the PSNR evaluation is not timed. pinmask is a fresh decode per iteration
count (deterministic: the k-iteration decode is the k-th iterate of a longer one) on a schedule of
counts, each timed whole (set-up, plans warm as the ADMM's torch FFT is). PSNR: peak 1 (scenes in
[0, 1]) after the least-squares gain (the normalisations differ) and the best of the 3 x 3 integer
shifts (the two decoders place the PSF's origin differently by up to a pixel), on the sensor
window.
"""
import importlib.util
import math
import os
import sys
import time
import types

import numpy as np

SNR_DB = 40.0
PATIENCE = 150  # the ADMM runs until its best PSNR is this many (or half its count) old
# Weight grids: decades, then the two half-decade neighbours (x 3, / 3) of the decade that won.
# LenslessPiCam's default tau is 1e-4; at 1e-4 and 1e-3 its PSNR curves on the DiffuserCam
# problem are identical (its soft threshold tau / mu2 is then 10 or more), so the grid goes down.
ADMM_TAUS = (1e-8, 1e-7, 1e-6, 1e-5, 1e-4)
PINMASK_LAMBDAS = (1e-5, 1e-4, 1e-3, 1e-2)  # relative to the capture's peak
PINMASK_TUNE_ITERS = 300  # pinmask's weight is chosen by the PSNR of a decode of this many
SCHEDULE = (5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 100, 120, 150, 200, 250, 300, 400, 500,
            700, 1000)
HERE = os.path.dirname(os.path.abspath(__file__))
# The shared data folder: $PINMASK_SHARED_DIR, else ../shared beside the repository (as
# scripts/demo-real).
HAND = os.path.join(os.environ.get("PINMASK_SHARED_DIR", os.path.join(HERE, "..", "..", "shared")),
                    "data", "real", "waller-lab-diffusercam-tutorial")


def import_lenslesspicam(path):
    """LenslessPiCam's ADMM class from the checkout at `path` (the folder holding lensless/).
    Shim: its package imports cv2 (OpenCV) at module level for image resizing and I/O that the
    ADMM never calls; without python3-opencv a stand-in module answers those attribute reads
    (constants) so the import succeeds. Returns (ADMM class, list of shims applied)."""
    if not os.path.isdir(os.path.join(path, "lensless", "recon")):
        raise SystemExit(f"--lenslesspicam {path}: no lensless/recon/ there (give the folder that "
                         "holds LenslessPiCam's lensless/ package)")
    shims = []
    if importlib.util.find_spec("cv2") is None:
        stub = types.ModuleType("cv2")

        def attr(name):
            if name.startswith("__"):
                raise AttributeError(name)
            return 0
        stub.__getattr__ = attr
        sys.modules["cv2"] = stub
        shims.append("cv2 (not installed): a stand-in module whose attributes read 0")
    sys.path.insert(0, os.path.abspath(path))
    from lensless.recon.admm import ADMM  # noqa: E402
    return ADMM, shims


def box_down(a, rounds):
    for _ in range(rounds):
        r, c = a.shape[0] // 2 * 2, a.shape[1] // 2 * 2
        a = a[:r, :c].reshape(r // 2, 2, c // 2, 2).mean(axis=(1, 3))
    return a


def photograph(name, rows, cols):
    """skimage's bundled photograph `name` (a PNG in skimage/data), grey, resized to rows x cols,
    in [0, 1]."""
    import skimage  # noqa: E402
    from skimage import color, io, transform  # noqa: E402
    im = io.imread(os.path.join(os.path.dirname(skimage.__file__), "data", name + ".png"))
    if im.ndim == 3:
        im = color.rgb2gray(im[..., :3])
    im = transform.resize(im.astype(np.float64), (rows, cols), anti_aliasing=True)
    im = im - im.min()
    return im / im.max()


def render(psf, scene, snr_db, seed):
    """The sensor capture: 'valid' linear convolution (scipy) plus Gaussian noise at snr_db."""
    from scipy.signal import fftconvolve  # noqa: E402
    clean = fftconvolve(scene, psf, mode="valid")
    sigma = np.sqrt(np.mean(clean ** 2)) * 10 ** (-snr_db / 20)
    return clean + np.random.default_rng(seed).normal(0.0, sigma, clean.shape)


def make_problem(name, psf, photo, seed):
    r, c = psf.shape  # sensor-sized PSF: the capture is r x c too
    scene = photograph(photo, 2 * r - 1, 2 * c - 1)
    capture = render(psf, scene, SNR_DB, seed)
    truth = scene[r - 1 - r // 2:r - 1 - r // 2 + r, c - 1 - c // 2:c - 1 - c // 2 + c]
    # The noise's standard deviation, as render drew it (for the data term's noise level).
    clean = render(psf, scene, math.inf, seed)
    sigma = np.sqrt(np.mean(clean ** 2)) * 10 ** (-SNR_DB / 20)
    return {"name": name, "psf": psf, "capture": capture, "truth": truth, "sigma": sigma}


def problems(pinmask, only=None):
    """The problems (built lazily), those whose name has a word of `only` when given."""
    def wanted(name):
        return not only or any(w.lower() in name.lower() for w in only)
    name = "DiffuserCam PSF, 300 x 400"
    if wanted(name) and os.path.exists(os.path.join(HAND, "psf_sample.tif")):
        from skimage import io as skio  # noqa: E402
        psf = skio.imread(os.path.join(HAND, "psf_sample.tif")).astype(np.float64)
        psf = np.maximum(psf - psf[5:15, 5:15].mean(), 0)
        yield make_problem(name, box_down(psf, 2), "coffee", 11)
    elif wanted(name):
        print(f"(no {HAND}: the DiffuserCam problem is skipped)")
    name = "pinhole array, exact PSF, 240 x 360"
    if wanted(name):
        mask = pinmask.generate(family="paper", seed=1)
        psf = np.asarray(pinmask.psf(mask, geometry="exact", size=(480, 720)))
        yield make_problem(name, box_down(psf, 1), "motorcycle_left", 12)
    name = "lensless pinhole array, 160 x 200"
    if wanted(name):
        cam = pinmask.Camera(object_distance_m=2.0, lens_focal_m=math.inf,
                             sensor_distance_m=0.020, wavelength_m=550e-9, pixel_pitch_m=5e-6,
                             pinhole_m=160e-6, sensor_cols=400, sensor_rows=320)
        mask = pinmask.generate(family="random", grid=10, holes=15, seed=3, camera=cam)
        psf = np.asarray(pinmask.psf(mask, geometry="exact", size=(320, 400)))
        yield make_problem(name, box_down(psf, 1), "chelsea", 13)


def psnr(x, ref):
    mse = np.mean((x - ref) ** 2)
    return 10 * np.log10(1.0 / max(mse, 1e-300))


def fit_psnr(x, truth):
    """PSNR after the least-squares gain, the best over the 3 x 3 integer shifts of x. Returns
    (PSNR, shift)."""
    best = (-np.inf, (0, 0))
    r, c = truth.shape
    core = truth[1:r - 1, 1:c - 1]
    for s in [(dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1)]:
        xs = x[1 + s[0]:r - 1 + s[0], 1 + s[1]:c - 1 + s[1]]
        a = float(np.vdot(xs, core) / max(np.vdot(xs, xs), 1e-300))
        best = max(best, (psnr(a * xs, core), s))
    return best


def run_admm(ADMM, torch, prob, tau, max_iters):
    """(PSNR per iterate, CPU s to each iterate from the decoder's construction, shift). Runs
    until the best PSNR is older than max(PATIENCE, half its iteration count), or max_iters."""
    psf = prob["psf"] / np.linalg.norm(prob["psf"])
    data = prob["capture"] / prob["capture"].max()
    psf_t = torch.from_numpy(psf.astype(np.float32)[None, :, :, None])
    data_t = torch.from_numpy(data.astype(np.float32)[None, :, :, None])
    t0 = time.process_time()
    recon = ADMM(psf_t, tau=tau)
    recon.set_data(data_t)
    recon.reset()
    spent = time.process_time() - t0
    curve, times, shift = [], [], (0, 0)
    for i in range(max_iters):
        t0 = time.process_time()
        recon._update(i)
        spent += time.process_time() - t0
        est = recon._convolver._crop(recon._image_est).clone()  # _form_image on a copy
        est[est < 0] = 0
        q, shift = fit_psnr(est[0, 0, :, :, 0].numpy().astype(np.float64), prob["truth"])
        curve.append(q)
        times.append(spent)
        k_best = int(np.argmax(curve)) + 1
        if i + 1 - k_best > max(PATIENCE, k_best // 2):
            break
    return curve, times, shift


def pinmask_decode(pinmask, prob, lam, iters, tol=0.0):
    cap = prob["capture"]
    psf = prob["psf"] / prob["psf"].sum()
    t0 = time.process_time()
    res = pinmask.decode(cap, psf=psf, method="tv", model="linear", nonneg=True,
                         lambda_=lam * np.abs(cap).max(), iters=iters, tol=tol, crop="none",
                         threads=1)
    t = time.process_time() - t0
    return np.asarray(res["image"], np.float64), t, res


def run_pinmask(pinmask, prob, lam):
    """(PSNR per scheduled iteration count, CPU s of each decode, shift)."""
    pinmask_decode(pinmask, prob, lam, 2)  # warm: FFT plans, as the ADMM's torch FFT is warm
    curve, times, shift = [], [], (0, 0)
    for k in SCHEDULE:
        x, t, _ = pinmask_decode(pinmask, prob, lam, k)
        q, shift = fit_psnr(x, prob["truth"])
        curve.append(q)
        times.append(t)
        if len(curve) >= 8 and curve[-1] - curve[-4] < 0.05 and k >= 300:
            break  # a plateau: the last three counts gained < 0.05 dB
    return curve, times, shift


def tune(grid, run_one, score):
    """The best row of run_one over the decades of `grid`, then over the two half-decade
    neighbours of the winner."""
    rows = {w: run_one(w) for w in grid}
    best = max(rows, key=lambda w: score(rows[w]))
    for w in (best / 3, best * 3):
        rows[w] = run_one(w)
    return rows[max(rows, key=lambda w: score(rows[w]))]


def admm_row(ADMM, torch, prob, tau, iters, out):
    curve, times, _ = run_admm(ADMM, torch, prob, tau, iters)
    counts = list(range(1, len(curve) + 1))
    b = best_of(curve, times, counts)
    b.update(weight=tau, ms_iter=1e3 * per_iteration(times, counts), curve=curve)
    out(f"{prob['name']:<38} {'  ADMM tau grid':<22} {tau:7.1e} {b['ms_iter']:8.2f} "
        f"{b['psnr']:9.2f} {b['iters']:7d} {b['cpu_s']:13.2f} {b['final']:9.2f}")
    return b


def pinmask_tune_row(pinmask, prob, lam, out):
    pinmask_decode(pinmask, prob, lam, 2)  # warm
    x, t, _ = pinmask_decode(pinmask, prob, lam, PINMASK_TUNE_ITERS)
    q = fit_psnr(x, prob["truth"])[0]
    out(f"{prob['name']:<38} {'  pinmask lambda grid':<22} {lam:7.1e} {'':>8} {q:9.2f} "
        f"{PINMASK_TUNE_ITERS:7d} {t:13.2f}")
    return {"weight": lam, "psnr": q}


def best_of(curve, times, counts):
    k = int(np.argmax(curve))
    return {"psnr": curve[k], "iters": counts[k], "cpu_s": times[k], "final": curve[-1]}


def per_iteration(times, counts):
    """CPU s per iteration: the slope between the second and the last point."""
    return (times[-1] - times[1]) / (counts[-1] - counts[1])


def run(pinmask, path, admm_iters, only=None, out=print):
    """The comparison; `only`: the problems whose name contains one of these words."""
    if not path:
        out("linear model: no --lenslesspicam PATH given, so the comparison against "
            "LenslessPiCam's ADMM is skipped (PATH: a checkout of LCAV/LenslessPiCam, the folder "
            "holding its lensless/ package; it needs Debian's python3-torch)")
        return []
    try:
        import torch  # noqa: E402
    except ImportError:
        out("linear model: python3-torch is not installed (scripts/bench-peers --setup installs "
            "it), so the comparison against LenslessPiCam's ADMM is skipped")
        return []
    torch.set_num_threads(1)
    ADMM, shims = import_lenslesspicam(path)
    out(f"LenslessPiCam's ADMM from {os.path.abspath(path)}; torch {torch.__version__}, 1 thread; "
        f"shims: {'; '.join(shims) if shims else 'none'}")
    out(f"{'problem':<38} {'decoder':<22} {'weight':>7} {'ms/iter':>8} {'best PSNR':>9} "
        f"{'at iter':>7} {'CPU s to best':>13} {'last PSNR':>9}")
    rows = []
    for prob in problems(pinmask, only):
        # LenslessPiCam: tau on its grid, each run up to admm_iters iterations.
        admm = tune(ADMM_TAUS, lambda tau: admm_row(ADMM, torch, prob, tau, admm_iters, out),
                    lambda b: b["psnr"])
        # pinmask: lambda on its grid by the PSNR of a PINMASK_TUNE_ITERS-iteration decode (its
        # PSNR rises to a plateau, no peak), then the schedule of counts at the chosen lambda.
        lam = tune(PINMASK_LAMBDAS, lambda lam: pinmask_tune_row(pinmask, prob, lam, out),
                   lambda b: b["psnr"])["weight"]
        curve, times, _ = run_pinmask(pinmask, prob, lam)
        counts = list(SCHEDULE[:len(curve)])
        pm = best_of(curve, times, counts)
        pm.update(weight=lam, ms_iter=1e3 * per_iteration(times, counts), curve=curve, times=times)
        # pinmask at the ADMM's best PSNR: its first scheduled count at or above it.
        k_eq = next((i for i, q in enumerate(pm["curve"]) if q >= admm["psnr"]), None)
        # pinmask's own stop (its default tolerance, no ground truth) at the chosen lambda.
        x, t_own, res = pinmask_decode(pinmask, prob, pm["weight"], max(SCHEDULE), tol=None)
        own = {"psnr": fit_psnr(x, prob["truth"])[0], "cpu_s": t_own,
               "iters": int(res["channels"][0]["iterations"])}
        # The ADMM's curve at its chosen tau, every 50 iterations: whether its best is a plateau
        # or the crest of an oscillation (an oracle stop picks either).
        out(f"{prob['name']:<38} ADMM PSNR every 50 iterations: " +
            " ".join(f"{q:.2f}" for q in admm["curve"][49::50]))
        for label, b in (("LenslessPiCam ADMM", admm), ("pinmask TV", pm)):
            out(f"{prob['name']:<38} {label:<22} {b['weight']:7.1e} {b['ms_iter']:8.2f} "
                f"{b['psnr']:9.2f} {b['iters']:7d} {b['cpu_s']:13.2f} {b['final']:9.2f}")
        if k_eq is not None:
            t_eq = pm["times"][k_eq]
            ratio = t_eq / admm["cpu_s"]
            out(f"{prob['name']:<38} {'pinmask @ ADMM best':<22} {pm['weight']:7.1e} "
                f"{'':>8} {pm['curve'][k_eq]:9.2f} {SCHEDULE[k_eq]:7d} {t_eq:13.2f} "
                f"{'':>9}  time / ADMM's = {ratio:.2f} ({'meets' if ratio <= 1 / 3 else 'misses'}"
                f" the 1/3 target)")
        else:
            ratio = None
            out(f"{prob['name']:<38} {'pinmask @ ADMM best':<22} never reaches "
                f"{admm['psnr']:.2f} dB within {max(SCHEDULE)} iterations")
        out(f"{prob['name']:<38} {'pinmask, own stop':<22} {pm['weight']:7.1e} {'':>8} "
            f"{own['psnr']:9.2f} {own['iters']:7d} {own['cpu_s']:13.2f}  "
            f"({pm['psnr'] - own['psnr']:.2f} dB below its best)")
        out(f"{prob['name']:<38} pinmask's last PSNR {pm['final']:.2f} dB "
            f"{'>=' if pm['final'] >= admm['psnr'] else '<'} the ADMM's best {admm['psnr']:.2f} dB")
        sys.stdout.flush()
        rows.append({"problem": prob["name"], "admm": admm, "pinmask": pm, "ratio": ratio,
                     "own": own})
    return rows

