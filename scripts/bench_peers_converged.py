"""What the oracle stop of scripts/bench-peers' linear comparison picks: for each problem of
scripts/bench_peers_linear.py, the best iterate of each decoder against the optimum of its own
objective (the comparison itself times decoders to their best PSNR; this says whether that best
is a converged estimate or a passing iterate).

Per problem it prints:
- LenslessPiCam's ADMM at its default penalties (mu1 1e-6, mu2 1e-5, mu3 4e-5) and the tau the
  comparison chose (ADMM_TAU below), every 100 iterations: PSNR, the data term
  1/2 ||crop(H x) - y||^2 over its value at the noise level (N sigma^2 / 2, in the ADMM's units),
  and its objective with its anisotropic TV (whether it still falls).
- The anisotropic TV's optimum: the same ADMM code with every penalty x PENALTY_SCALE (so it
  converges within the run) at the taus that match pinmask's lambdas (tau = lambda c, c = the PSF's
  sum over its L2 norm: the two decoders' normalisations), after ANISO_ITERS iterations, with the
  objective's relative fall over the last 100 (how converged).
- pinmask's isotropic TV at the same lambdas after 300, 700 and PINMASK_LONG iterations, with its
  objective's relative fall over the last 10 % (how converged).
"""
import time
import warnings

import numpy as np

import bench_peers_linear as bpl

# The tau the comparison chose per problem (docs/benchmarks.md's table).
ADMM_TAU = {"DiffuserCam": 3.3e-6, "exact PSF": 1e-5, "lensless": 1e-6}
ADMM_ITERS = 1000
LAMBDAS = (3e-5, 1e-4, 3e-4, 1e-3, 3e-3)  # pinmask's lambda relative to the capture's peak
PENALTY_SCALE = 1e4
ANISO_ITERS = 1000
PINMASK_COUNTS = (300, 700)
PINMASK_LONG = 3000


def admm_objective(recon, torch, data_t, tau, x):
    """(1/2 ||crop(H x) - y||^2, anisotropic TV of x) in the ADMM's units."""
    res = recon._convolver._crop(recon._convolver.convolve(x)) - data_t
    d = torch.stack((torch.roll(x, 1, dims=-3) - x, torch.roll(x, 1, dims=-2) - x), dim=-1)
    return 0.5 * float((res.double() ** 2).sum()), float(d.abs().double().sum())


def admm_path(ADMM, torch, prob, tau, iters, scale, every, out):
    """Runs the ADMM (penalties x scale); prints every `every` iterations when out is given.
    Returns (last PSNR, best PSNR, its iteration, objective's relative fall over the last 100)."""
    psf = prob["psf"] / np.linalg.norm(prob["psf"])
    peak = prob["capture"].max()
    data = prob["capture"] / peak
    psf_t = torch.from_numpy(psf.astype(np.float32)[None, :, :, None])
    data_t = torch.from_numpy(data.astype(np.float32)[None, :, :, None])
    recon = ADMM(psf_t, tau=tau, mu1=1e-6 * scale, mu2=1e-5 * scale, mu3=4e-5 * scale)
    recon.set_data(data_t)
    recon.reset()
    noise_level = 0.5 * data.size * (prob["sigma"] / peak) ** 2
    best, objs = (-np.inf, 0), {}
    for i in range(1, iters + 1):
        recon._update(i - 1)
        if i % every == 0 or i == iters - 100:
            est = recon._convolver._crop(recon._image_est).clone()
            est[est < 0] = 0
            q = bpl.fit_psnr(est[0, 0, :, :, 0].numpy().astype(np.float64), prob["truth"])[0]
            best = max(best, (q, i))
            f, tv = admm_objective(recon, torch, data_t, tau, torch.clamp(recon._image_est, min=0))
            objs[i] = f + tau * tv
            if out and i % every == 0:
                out(f"  {i:5d} PSNR {q:6.2f}  data / noise level {f / noise_level:6.3f}  "
                    f"objective {objs[i]:.5e}")
    fall = (objs[iters - 100] - objs[iters]) / objs[iters]
    return q, best[0], best[1], fall


def pinmask_run(pinmask, prob, lam, iters):
    cap = prob["capture"]
    with warnings.catch_warnings():  # the weights are set on purpose, whatever auto would choose
        warnings.simplefilter("ignore")
        res = pinmask.decode(cap, psf=prob["psf"] / prob["psf"].sum(), method="tv",
                             model="linear", nonneg=True, lambda_=lam * np.abs(cap).max(),
                             iters=iters, tol=0.0, crop="none", threads=1)
    q = bpl.fit_psnr(np.asarray(res["image"], np.float64), prob["truth"])[0]
    return q, np.asarray(res["channels"][0]["history"])[:, 2]


def run(pinmask, path, only=None, out=print):
    if not path:
        out("--converged: no --lenslesspicam PATH given, so nothing is measured")
        return
    import torch  # noqa: E402
    torch.set_num_threads(1)
    ADMM, _ = bpl.import_lenslesspicam(path)
    for prob in bpl.problems(pinmask, only):
        t0 = time.process_time()
        tau = next(v for k, v in ADMM_TAU.items() if k.lower() in prob["name"].lower())
        c = prob["psf"].sum() / np.linalg.norm(prob["psf"])
        out(f"{prob['name']}: LenslessPiCam ADMM, default penalties, tau {tau:.1e}")
        last, best, at, fall = admm_path(ADMM, torch, prob, tau, ADMM_ITERS, 1.0, 100, out)
        out(f"  best {best:.2f} dB at {at}, last {last:.2f}; objective fell {fall:.1e} over the "
            "last 100 iterations")
        for lam in LAMBDAS:
            a_last, a_best, a_at, a_fall = admm_path(ADMM, torch, prob, lam * c, ANISO_ITERS,
                                                     PENALTY_SCALE, 50, None)
            q = [pinmask_run(pinmask, prob, lam, k)[0] for k in PINMASK_COUNTS]
            q_long, obj = pinmask_run(pinmask, prob, lam, PINMASK_LONG)
            p_fall = (obj[int(0.9 * PINMASK_LONG) - 1] - obj[-1]) / obj[-1]
            out(f"  lambda {lam:.0e} (tau {lam * c:.1e}): anisotropic TV (ADMM, penalties x"
                f"{PENALTY_SCALE:.0e}) {a_last:.2f} dB after {ANISO_ITERS} (best {a_best:.2f} at "
                f"{a_at}; objective fell {a_fall:.1e} over the last 100); pinmask isotropic TV " +
                ", ".join(f"{v:.2f}" for v in q) + f", {q_long:.2f} dB after " +
                ", ".join(str(k) for k in PINMASK_COUNTS) + f", {PINMASK_LONG} (objective fell "
                f"{p_fall:.1e} over the last 10 %)")
        out(f"  ({time.process_time() - t0:.0f} CPU s)")
