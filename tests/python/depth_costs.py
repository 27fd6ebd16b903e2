"""The depth costs compared in docs/depth.md section 3b (scripts/depthmap_costs.py), in numpy:
per plane u, PSF K_u normalised to sum 1, capture spectrum Y:
  residual  the box mean of r_u^2, r_u = ifft(nsr / (|K_u|^2 + nsr) Y), nsr 0.01 (pinmask's);
  evidence  the local Gaussian marginal likelihood: the box mean of e_u^2 with the whitened
            capture e_u = ifft(Y / sqrt(D_u)), D_u = |K_u|^2 A / (lambda + eps) + s^2, plus the
            mean over frequencies of log D_u; lambda the discrete Laplacian's eigenvalue (the
            1/f^2 prior), s^2 the capture's power near Nyquist (lambda > 6), A by matching the
            capture's power to the planes' mean |K|^2 / lambda;
  split     the same evidence with its quadratic term split into the sensor-space residual of
            the MAP estimate x_u and the scene-space prior |grad x_u|^2 / A (over the frame the
            two add up to e_u's energy), box means of each;
  joint     one step of a joint image/depth refinement started from the residual cost's labels:
            the image x (each pixel from its plane's Wiener estimate), the capture it predicts
            (each label's pixels blurred by its plane's PSF, summed), the residual r, and per
            pixel and plane j the change of |r|^2 if the pixel moved to j, linearised:
            -2 x (K_j^T r - K_l^T r) + x'^2 |K_j - K_l|^2 (x' the pixel's departure from its
            15 px box mean), its box mean over 31 px; the lowest change wins.
costs() returns the cost volume (planes first); its argmin over planes is the label."""
import numpy as np
from scipy.ndimage import uniform_filter

EPS = 1e-4


def laplacian_eigen(rows, cols):
    fy, fx = np.fft.fftfreq(rows)[:, None], np.fft.fftfreq(cols)[None, :]
    return 4 * np.sin(np.pi * fy) ** 2 + 4 * np.sin(np.pi * fx) ** 2


def costs(y, psfs, kind, window=121):
    Y, n = np.fft.fft2(y), y.size
    ks = [np.fft.fft2(np.fft.ifftshift(p / p.sum())) for p in psfs]
    lam = laplacian_eigen(*y.shape)
    power = abs(Y) ** 2 / n
    s2 = power[lam > 6.0].mean()
    g = np.mean([abs(k) ** 2 for k in ks], 0) / (lam + EPS)
    a = max(power.sum() - s2 * n, 1e-12) / g.sum()
    out = []
    if kind == "joint":
        return joint(y, ks, costs(y, psfs, "residual", window).argmin(0))
    for k in ks:
        if kind == "residual":
            q = np.real(np.fft.ifft2(0.01 / (abs(k) ** 2 + 0.01) * Y)) ** 2
            out.append(uniform_filter(q, window, mode="wrap"))
            continue
        s = a / (lam + EPS)
        d = abs(k) ** 2 * s + s2
        if kind == "evidence":
            q = np.real(np.fft.ifft2(Y / np.sqrt(d))) ** 2
        else:
            xf = np.conj(k) * s * Y / d
            x = np.real(np.fft.ifft2(xf))
            r = y - np.real(np.fft.ifft2(k * xf))
            gx, gy = np.roll(x, -1, 1) - x, np.roll(x, -1, 0) - x
            q = r ** 2 / s2 + (gx ** 2 + gy ** 2 + EPS * x ** 2) / a
        out.append(uniform_filter(q, window, mode="wrap") + np.log(d).mean())
    return np.array(out)


def joint(y, ks, label):
    """The labels after one linearised joint step (see the module's docstring), as a cost
    volume (its argmin is the new label)."""
    Y = np.fft.fft2(y)
    xs = np.array([np.real(np.fft.ifft2(np.conj(k) / (abs(k) ** 2 + 0.01) * Y)) for k in ks])
    x = np.take_along_axis(xs, label[None], 0)[0]
    pred = sum(np.real(np.fft.ifft2(ks[j] * np.fft.fft2(x * (label == j))))
               for j in range(len(ks)) if (label == j).any())
    r = np.fft.fft2(y - pred)
    back = np.array([np.real(np.fft.ifft2(np.conj(k) * r)) for k in ks])
    cur = np.take_along_axis(back, label[None], 0)[0]
    dx = x - uniform_filter(x, 15, mode="wrap")
    e = np.array([[np.mean(abs(a - b) ** 2) for b in ks] for a in ks])
    d = -2 * x[None] * (back - cur[None]) + dx[None] ** 2 * e[:, label]
    return np.array([uniform_filter(dj, 31, mode="wrap") for dj in d])
