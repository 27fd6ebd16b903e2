"""An independent forward model of multi-plane scenes for the depthmap tests and the table of
docs/depth.md: each plane's exact-geometry PSF is drawn here in numpy from the mask's pinhole
cells and the camera (docs/design.md section 2, Eq. (3) of the paper), never by pinmask's code.

Geometry: tiled-mask cell (i, j) sits at s = ((i + 1/2) - N_t/2, (j + 1/2) - N_t/2) d from the
mask centre; its spot is centred at M(u) s / w pixels from the optical axis, which lies at the
frame's centre (rows/2, cols/2, a pixel corner for even sides), with M(u) = 1 - f/f' + f/u. The
spot is a geometric box of side d |M(u)| / w pixels (the pinhole's image), integrated exactly
over the pixels (pinmask uses its own kernel model: the mismatch is part of the test). Each
pinhole weighs 1/K. A scene is a sum of planes (no occlusion): plane k's texture, zero outside
its region, circularly convolved with its PSF over the frame, then photon noise.
"""
import json

import numpy as np

# The close-range camera of the depthmap tests, table and axial figure (docs/depth.md): a
# machine-vision sensor behind a 25 mm lens, u = 0.5 m (20 f), 512 x 512 pixels.
MACHINE_VISION = dict(object_distance_m=0.5, lens_focal_m=0.025, sensor_distance_m=0.020,
                      wavelength_m=530e-9, pixel_pitch_m=3.45e-6, pinhole_m=115e-6,
                      sensor_cols=512, sensor_rows=512)


def magnification(cam, u):
    return 1.0 - cam["sensor_distance_m"] / cam["lens_focal_m"] + cam["sensor_distance_m"] / u


def exact_psf(mask_json, u, rows, cols):
    cam, pat = mask_json["optics"], mask_json["pattern"]
    n = pat["n"]
    tiles = pat["tiles"]
    d, w = cam["pinhole_m"], cam["pixel_pitch_m"]
    side = d * abs(magnification(cam, u)) / w
    pitch = d * magnification(cam, u) / w
    cells = [(r, c) for r, c in pat["pinholes"]]
    ntr, ntc = n * tiles[0], n * tiles[1]
    er, ec = np.arange(rows + 1), np.arange(cols + 1)
    out = np.zeros((rows, cols))
    for tr in range(tiles[0]):
        for tc in range(tiles[1]):
            for r, c in cells:
                cy = rows / 2 + (tr * n + r + 0.5 - ntr / 2) * pitch
                cx = cols / 2 + (tc * n + c + 0.5 - ntc / 2) * pitch
                wy = np.clip(np.minimum(er[1:], cy + side / 2) - np.maximum(er[:-1], cy - side / 2), 0, None)
                wx = np.clip(np.minimum(ec[1:], cx + side / 2) - np.maximum(ec[:-1], cx - side / 2), 0, None)
                out += np.outer(wy, wx) / (side * side)
    return out / len(cells)


def blur(x, psf):
    """Circular convolution with the PSF whose centre (rows/2, cols/2) is the origin."""
    h = np.fft.rfft2(np.fft.ifftshift(psf))
    return np.fft.irfft2(np.fft.rfft2(x) * h, s=x.shape)


def texture(rows, cols, rng):
    """A piecewise-constant texture: random discs and bars of random grey levels on 0.2."""
    yy, xx = np.mgrid[0:rows, 0:cols]
    t = np.full((rows, cols), 0.2)
    for _ in range(rows * cols // 900):
        cy, cx = rng.integers(0, rows), rng.integers(0, cols)
        r = rng.integers(3, 12)
        if rng.random() < 0.5:
            t[(yy - cy) ** 2 + (xx - cx) ** 2 < r * r] = rng.random()
        else:
            t[(abs(yy - cy) < r) & (abs(xx - cx) < 2)] = rng.random()
    return t


def scene(mask_json, distances, rows, cols, photons, seed):
    """Vertical bands, one per distance (left to right), over a frame whose outer `border` pixels
    are dark. Returns (capture, truth depth map with NaN in the border, texture, valid mask)."""
    rng = np.random.default_rng(seed)
    tex = texture(rows, cols, rng)
    border = rows // 8
    yy, xx = np.mgrid[0:rows, 0:cols]
    inside = (yy >= border) & (yy < rows - border) & (xx >= border) & (xx < cols - border)
    band = np.minimum(((xx - border) * len(distances)) // (cols - 2 * border), len(distances) - 1)
    truth = np.where(inside, np.asarray(distances)[band], np.nan)
    clean = np.zeros((rows, cols))
    for k, u in enumerate(distances):
        clean += blur(tex * inside * (band == k), exact_psf(mask_json, u, rows, cols))
    capture = rng.poisson(np.maximum(clean, 0) * photons) / photons
    return capture, truth, tex * inside, inside


def load(path):
    with open(path) as f:
        return json.load(f)


def wiener(capture, psf, nsr):
    """Wiener estimate with the PSF normalised to sum 1 (numpy, for the single-plane baseline)."""
    h = np.fft.rfft2(np.fft.ifftshift(psf / psf.sum()))
    return np.fft.irfft2(np.conj(h) / (abs(h) ** 2 + nsr) * np.fft.rfft2(capture), s=capture.shape)


def psnr_fitted(x, truth, region):
    """PSNR (peak 1) of x against truth on region after the least-squares gain (the decodes
    normalise the PSF to sum 1, the capture holds every tile's light)."""
    a, b = x[region], truth[region]
    gain = float(a @ b) / float(a @ a)
    return 10 * np.log10(1.0 / np.mean((gain * a - b) ** 2))


def measure(run_depthmap, read_tiff, mask_path, planes, frm, to, steps, size, photons, seed,
            nsr=0.01, baseline=True):
    """One row: the scene of `planes` rendered here, depthmap run by run_depthmap(capture, frm,
    to, steps) -> (out_dir, summary), figures against the truth; baseline=False skips the best
    single-plane decode (16 numpy decodes)."""
    mj = load(mask_path)
    capture, truth, tex, inside = scene(mj, planes, size, size, photons, seed)
    out, summary = run_depthmap(capture, frm, to, steps)
    depth = read_tiff(out / "depth.tif")
    aif = read_tiff(out / "all_in_focus.tif")
    inv = lambda x: 1.0 / np.asarray(x, dtype=float)
    spacing = (inv(frm) - (0.0 if np.isinf(to) else inv(to))) / (steps - 1)
    err = inv(depth[inside]) - inv(truth[inside])
    best_single = None if not baseline else max(psnr_fitted(wiener(capture, exact_psf(mj, u, size, size), nsr), tex, inside)
                      for u in 1.0 / np.linspace(inv(frm), 0.0 if np.isinf(to) else inv(to), steps))
    return {
        "rms_m": float(np.sqrt(np.mean((depth[inside] - truth[inside]) ** 2))),
        "rms_planes": float(np.sqrt(np.mean(err ** 2)) / spacing),
        "within_spacing": float(np.mean(abs(err) <= spacing)),
        "aif_psnr_db": psnr_fitted(aif, tex, inside),
        "single_best_psnr_db": best_single,
        "capture_depth_m": summary["capture_depth_m"],
        "capture_error_planes": float(abs(inv(summary["capture_depth_m"]) - inv(planes[0])) / spacing)
        if len(planes) == 1 else None,
    }


# The four cameras of docs/depth.md's table, as pinmask.Camera keywords, with the range of
# object distances each is meant for. The pinhole side gives 8 px per cell at the design distance
# (d = 8 w / M(u0)). "paper" is the paper's prototype (design/optics/camera.hpp's paper_camera).
CAMERAS = {
    "paper": (dict(object_distance_m=6.0, lens_focal_m=0.120, sensor_distance_m=0.055,
                   wavelength_m=550e-9, pixel_pitch_m=30e-6, pinhole_m=440e-6,
                   sensor_cols=720, sensor_rows=480), 2.0, 6.0),
    "machine vision": (MACHINE_VISION, 0.45, 1.5),
    "phone": (dict(object_distance_m=0.3, lens_focal_m=0.0044, sensor_distance_m=0.0042,
                   wavelength_m=530e-9, pixel_pitch_m=1.12e-6, pinhole_m=150.6e-6,
                   sensor_cols=512, sensor_rows=512), 0.2, 1.0),
    "visible 35 mm": (dict(object_distance_m=0.5, lens_focal_m=0.035, sensor_distance_m=0.022,
                           wavelength_m=530e-9, pixel_pitch_m=2.4e-6, pinhole_m=46.3e-6,
                           sensor_cols=512, sensor_rows=512), 0.3, 1.2),
}

# Scene kinds, each as positions t in [0, 1] along the range in 1/u (0: the near end, 1: the
# far end), left to right: two and three planes in bands, a slanted plane (1/u linear across the
# columns, drawn as 24 strips), half textured (left) and half flat (right, a constant grey),
# and one plane filling the scene.
SCENE_KINDS = {
    "two planes": [0.2, 0.8],
    "three planes": [0.1, 0.5, 0.9],
    "slanted plane": list(0.05 + 0.9 * (np.arange(24) + 0.5) / 24),
    "half flat": [0.25, 0.75],
}


def range_inverse(near, far, t):
    """1/u at position t of the range [near, far] in 1/u."""
    return 1.0 / near + np.asarray(t, dtype=float) * (1.0 / far - 1.0 / near)


def kind_scene(mask_json, positions, near, far, size, photons, seed, flat_right=False):
    """Vertical bands at the given range positions (left to right) over a size x size frame with
    a dark border of size/8. flat_right: the right half's texture is a constant 0.5 (no
    structure: its depth cannot be read). Returns (capture, truth distance map with NaN in the
    border, texture, inside, flat region)."""
    rng = np.random.default_rng(seed)
    tex = texture(size, size, rng)
    border = size // 8
    yy, xx = np.mgrid[0:size, 0:size]
    inside = (yy >= border) & (yy < size - border) & (xx >= border) & (xx < size - border)
    n = len(positions)
    band = np.clip(((xx - border) * n) // (size - 2 * border), 0, n - 1)
    flat = inside & (band >= n // 2) if flat_right else np.zeros_like(inside)
    tex = np.where(flat, 0.5, tex)
    u = 1.0 / range_inverse(near, far, positions)
    clean = np.zeros((size, size))
    for k in range(n):
        clean += blur(tex * inside * (band == k), exact_psf(mask_json, u[k], size, size))
    capture = rng.poisson(np.maximum(clean, 0) * photons) / photons
    return capture, np.where(inside, u[band], np.nan), tex * inside, inside, flat


def region_decode(capture, truth, mask_json, nsr):
    """Each region decoded with its own true PSF (numpy Wiener): the reference the all-in-focus
    image is compared with."""
    out = np.zeros_like(capture)
    for u in np.unique(truth[np.isfinite(truth)]):
        region = truth == u
        out[region] = wiener(capture, exact_psf(mask_json, u, *capture.shape), nsr)[region]
    return out


def measure_kind(run_depthmap, mask_path, kind, near, far, steps, size, photons, seed,
                 nsr=0.01):
    """One row of the four-camera table: the scene `kind` (a SCENE_KINDS name, or a float: one
    plane at that range position), depthmap run by run_depthmap(capture, near, far, steps) ->
    pinmask.depthmap's result over the camera's range, figures against the truth on the
    textured pixels."""
    mj = load(mask_path)
    positions = [kind] if isinstance(kind, float) else SCENE_KINDS[kind]
    capture, truth, tex, inside, flat = kind_scene(mj, positions, near, far, size, photons,
                                                   seed, flat_right=(kind == "half flat"))
    r = run_depthmap(capture, near, far, steps)
    depth, conf, aif = r["depth_m"], r["confidence"], r["all_in_focus"]
    spacing = (1.0 / near - 1.0 / far) / (steps - 1)
    textured = inside & ~flat
    err = 1.0 / depth[textured] - 1.0 / truth[textured]
    within = abs(err) <= spacing
    sure = conf[textured] >= 0.5
    return {
        "within_spacing": float(np.mean(within)),
        "rms_planes": float(np.sqrt(np.mean(err ** 2)) / spacing),
        "median_error_planes": float(np.median(err) / spacing),
        "confident_share": float(np.mean(sure)),
        "within_when_confident": float(np.mean(within[sure])) if sure.any() else None,
        "flat_confidence_median": float(np.median(conf[flat])) if flat.any() else None,
        "aif_psnr_db": psnr_fitted(aif, tex, textured),
        "true_psf_psnr_db": psnr_fitted(region_decode(capture, truth, mj, nsr), tex, textured),
        "capture_depth_m": r["capture_depth_m"],
        # One plane: the whole-capture estimates' errors in plane spacings (frame-mean cost,
        # evidence).
        "capture_error_planes": whole_error(r["capture_depth_m"], truth, inside, spacing),
        "evidence_error_planes": whole_error(r["capture_evidence_depth_m"], truth, inside,
                                             spacing),
    }


def whole_error(estimate_m, truth, inside, spacing):
    """|1/estimate - 1/truth| in plane spacings for a scene of one plane, else None."""
    u = np.unique(truth[inside])
    if len(u) != 1 or estimate_m is None:
        return None
    return float(abs(1.0 / estimate_m - 1.0 / u[0]) / spacing)
