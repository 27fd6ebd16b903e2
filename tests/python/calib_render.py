"""A point-source capture through a fabricated coded mask, rendered with numpy alone (no pinmask
PSF code): the calibration tests' truth.

Physics (thin lens at the mask, point source on the axis at u):
- the pinhole of mask cell (R, C) images at m_u * xi on the sensor, xi its centre on the mask
  (the tiled mask centred on the axis, the axis at the frame's centre), m_u = f (1/f - 1/f' + 1/u);
  the fabricated mask is rotated by t (counter-clockwise on screen, rows down) and its pitch and
  pinhole side are scaled;
- each spot is the Fresnel diffraction pattern of the square pinhole (side d), separable along
  the mask's axes: per axis I(x) = a |J(a x)|^2 / 4, J(v) = int_{-1}^{1} exp(i pi (N s^2 - v s)) ds,
  a = d w / (lambda f), N = d^2 |1/f - 1/f' + 1/u| / (4 lambda). Its Fourier transform is the
  pupil's autocorrelation in closed form, I^(f) = (1/2) (2 - |tau|) sinc(N tau (2 - |tau|)),
  tau = 2 f / a (zero beyond |tau| = 2): the spots are band-limited, so the frame is rendered
  exactly in the Fourier domain, the pixel's box integral being the factor sinc(fx) sinc(fy)
  and each spot's sub-pixel position a phase (one matrix product over the spots). The grid is
  padded by at least `pad` pixels on each side; the cyclic transform still wraps the tails'
  far light (sinc^2 falls as 1/x^2) back into the frame, a smooth pedestal falling as 1/pad^2
  (measured on the NIR crop: 0.029, 0.0079, 0.0021 counts per pixel from pad 1024 to 2048,
  4096, 8192), so the frame is extrapolated from pads P and 2P: (4 I(2P) - I(P)) / 3 (within
  0.001 counts of pad 8192's limit there, against a leak of 0.23);
- the opaque film passes 10^-OD of the light per unit area (a geometric shadow, 4 x 4
  sub-samples per pixel) over the footprint of the tiled mask outside the open pinholes;
- Poisson photons, Gaussian read noise, a constant background (dark level).
`od_by_definition` is the optical density the project defines (optimize/simulate/noise_model.hpp: a
closed cell passes 10^-OD of one pinhole's flux) for such a film."""
import numpy as np
import scipy.fft


def m_u(cam):
    return cam.sensor_distance_m * (1 / cam.sensor_distance_m - 1 / cam.lens_focal_m
                                    + 1 / cam.object_distance_m)


def profile_ft(f, a, n_f):
    """Fourier transform of the per-axis intensity profile (pixel units), f in cycles/px."""
    tau = np.abs(2 * f / a)
    inside = tau < 2
    t = np.where(inside, tau, 0.0)
    return np.where(inside, 0.5 * (2 - t) * np.sinc(n_f * t * (2 - t)), 0.0)


def profile(x, a, n_f, samples=600):
    """The per-axis intensity a |J(a x)|^2 / 4 by Gauss-Legendre quadrature (for checks)."""
    s, w = np.polynomial.legendre.leggauss(samples)
    v = a * np.asarray(x, dtype=float)
    phase = np.pi * (n_f * s[None, :] ** 2 - v[:, None] * s[None, :])
    return a * np.abs((w[None, :] * np.exp(1j * phase)).sum(axis=1)) ** 2 / 4


def spot_centres(mask, rows, cols, rotation_deg, pitch_scale, shift=(0.0, 0.0)):
    """(cells, x, y, pitch): every open cell of the tiled mask and its spot centre (index
    coordinates); `pitch_scale` one scale or (along the mask's columns, along its rows), `shift`
    (x, y) moves the whole mask on the sensor."""
    cam, pat = mask.camera, mask.pattern
    sx, sy = np.broadcast_to(np.asarray(pitch_scale, float), (2,))
    pitch = m_u(cam) * cam.pinhole_m / cam.pixel_pitch_m
    t = np.deg2rad(rotation_deg)
    ct, st = np.cos(t), np.sin(t)
    cells = [(r + tr * pat.n, c + tc * pat.n) for tr in range(pat.tiles_rows)
             for tc in range(pat.tiles_cols) for (r, c) in pat.pinholes]
    cr = np.array([c[0] for c in cells], float) + 0.5 - pat.n * pat.tiles_rows / 2
    cc = np.array([c[1] for c in cells], float) + 0.5 - pat.n * pat.tiles_cols / 2
    x = (cols - 1) / 2 + shift[0] + pitch * (sx * ct * cc + sy * st * cr)
    y = (rows - 1) / 2 + shift[1] + pitch * (-sx * st * cc + sy * ct * cr)
    return cells, x, y, pitch * sx


def spots(mask, rows, cols, rotation_deg=0.0, pitch_scale=1.0, side_scale=1.0, missing=(),
          flux=1e6, wavelengths=None, pad=1024, shift=(0.0, 0.0)):
    """The noiseless spots, extrapolated to no wrap-around from pads `pad` and 2 `pad`."""
    args = (mask, rows, cols, rotation_deg, pitch_scale, side_scale, missing, flux, wavelengths,
            shift)
    near = spots_padded(*args, pad)
    return (4 * spots_padded(*args, 2 * pad) - near) / 3


def spots_padded(mask, rows, cols, rotation_deg, pitch_scale, side_scale, missing, flux,
                 wavelengths, shift, pad):
    """The noiseless spots (counts): `flux` through a pinhole of the design's side (a
    fabricated side s passes s^2 of it), each wavelength (lambda, weight) of `wavelengths`
    (default: the camera's centre wavelength alone) weighted."""
    cam = mask.camera
    cells, x, y, _ = spot_centres(mask, rows, cols, rotation_deg, pitch_scale, shift)
    keep = np.array([c not in set(missing) for c in cells])
    x, y = x[keep] + pad, y[keep] + pad
    R = scipy.fft.next_fast_len(rows + 2 * pad)
    C = scipy.fft.next_fast_len(cols + 2 * pad, True)
    d = cam.pinhole_m * side_scale
    inv_z = abs(1 / cam.sensor_distance_m - 1 / cam.lens_focal_m + 1 / cam.object_distance_m)
    t = np.deg2rad(rotation_deg)
    ct, st = np.cos(t), np.sin(t)
    fy_all = np.fft.fftfreq(R)
    fx_all = np.fft.rfftfreq(C)
    spec = np.zeros((R, C // 2 + 1), complex)
    for lam, weight in wavelengths or [(cam.wavelength_m, 1.0)]:
        a = d * cam.pixel_pitch_m / (lam * cam.sensor_distance_m)
        n_f = d * d * inv_z / (4 * lam)
        reach = a * (abs(ct) + abs(st)) * 1.0001
        iy = np.nonzero(np.abs(fy_all) <= reach)[0]
        ix = np.nonzero(np.abs(fx_all) <= reach)[0]
        fy, fx = fy_all[iy][:, None], fx_all[ix][None, :]
        fu, fv = ct * fx - st * fy, st * fx + ct * fy
        kern = profile_ft(fu, a, n_f) * profile_ft(fv, a, n_f) * np.sinc(fx) * np.sinc(fy)
        ey = np.exp(-2j * np.pi * fy_all[iy][:, None] * y[None, :])
        ex = np.exp(-2j * np.pi * fx_all[ix][:, None] * x[None, :])
        spec[np.ix_(iy, ix)] += weight * flux * side_scale ** 2 * kern * (ey @ ex.T)
    img = scipy.fft.irfft2(spec, s=(R, C))
    return img[pad:pad + rows, pad:pad + cols]


def film_leak(mask, rows, cols, rotation_deg, pitch_scale, side_scale, od, flux, sub=4,
              shift=(0.0, 0.0)):
    """Counts per pixel through the opaque film (transmission 10^-od per unit area) for the
    light that passes `flux` through a pinhole of the design's side (geometry as spot_centres)."""
    cam, pat = mask.camera, mask.pattern
    sx, sy = np.broadcast_to(np.asarray(pitch_scale, float), (2,))
    pitch = m_u(cam) * cam.pinhole_m / cam.pixel_pitch_m
    px, py = pitch * sx, pitch * sy
    side_px = m_u(cam) * cam.pinhole_m * side_scale / cam.pixel_pitch_m
    clear_per_px = flux / (m_u(cam) * cam.pinhole_m / cam.pixel_pitch_m) ** 2
    open_grid = np.zeros((pat.n, pat.n), bool)
    for (r, c) in pat.pinholes:
        open_grid[r, c] = True
    t = np.deg2rad(rotation_deg)
    ct, st = np.cos(t), np.sin(t)
    nr, nc = pat.n * pat.tiles_rows, pat.n * pat.tiles_cols
    off = (np.arange(sub) + 0.5) / sub - 0.5
    out = np.zeros((rows, cols))
    xs = (np.arange(cols)[:, None] + off[None, :]).ravel() - (cols - 1) / 2 - shift[0]
    for r in range(rows):
        ys = r + off - (rows - 1) / 2 - shift[1]
        dx, dy = xs[None, :], ys[:, None]
        # Mask coordinates in cells from the tiled mask's corner (inverse of spot_centres).
        u = (ct * dx - st * dy) / px + nc / 2
        v = (st * dx + ct * dy) / py + nr / 2
        inside = (u >= 0) & (u < nc) & (v >= 0) & (v < nr)
        iu, iv = np.floor(u).astype(int), np.floor(v).astype(int)
        opened = inside & open_grid[np.clip(iv, 0, nr - 1) % pat.n, np.clip(iu, 0, nc - 1) % pat.n]
        clear = (opened & (np.abs(u - iu - 0.5) < 0.5 * side_px / px)
                 & (np.abs(v - iv - 0.5) < 0.5 * side_px / py))
        opaque = inside & ~clear
        out[r] = opaque.reshape(sub, cols, sub).mean(axis=(0, 2))
    return out * clear_per_px * 10.0 ** -od


def od_by_definition(od, pitch_scale, side_scale):
    """The project's optical density (a closed cell passes 10^-OD of one pinhole's flux) of a
    film of physical density `od` whose cells are pitch_scale and pinholes side_scale of the
    design's: a closed cell's area is (pitch_scale / side_scale)^2 pinholes'."""
    return od - 2 * np.log10(pitch_scale / side_scale)


def noisy(clean, seed, background=20.0, read_noise=3.0):
    rng = np.random.default_rng(seed)
    photons = rng.poisson(np.clip(clean + background, 0, None))
    return photons + rng.normal(0, read_noise, clean.shape)
