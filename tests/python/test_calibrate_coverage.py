"""Do calibrate's standard errors cover the truth? Point-source captures of perturbed masks are
rendered by tests/python/calib_render.py (numpy alone: Fresnel spots of square pinholes in
closed form, pixel-integrated, the film's leak as a geometric shadow, Poisson and read noise),
calibrated by pinmask, and each parameter's 1-sigma interval is checked against the truth over
independent noise seeds.

The always-on test runs a few seeds on a small crop; the measurement of docs/calibration.md
(50 seeds on three setups) is scripts/calibrate-coverage.py, or this file with PINMASK_SLOW=1."""
import os
import sys

import numpy as np
import pytest

import pinmask

sys.path.insert(0, os.path.dirname(__file__))
import calib_render as cr  # noqa: E402

ROTATION, PITCH_SCALE, SIDE_SCALE, OD = 0.8, 1.004, 0.94, 3.0


def phone(rows, cols):
    """The issue's phone-like camera: 1.12 um pixels, f' = 4.4 mm, sensor at 4.2 mm, 530 nm,
    u = 0.3 m; the pinhole (= cell) solved for 16 px per cell at u."""
    cam = pinmask.Camera(object_distance_m=0.3, lens_focal_m=4.4e-3, sensor_distance_m=4.2e-3,
                         wavelength_m=530e-9, pixel_pitch_m=1.12e-6, pinhole_m=20e-6,
                         sensor_cols=4032, sensor_rows=3024)
    cam.pinhole_m = 16 * cam.pixel_pitch_m / cr.m_u(cam)
    return cam, 16


def nir(rows, cols):
    """The NIR camera of the calibration matrix: 5.86 um pixels, f' = 75 mm, sensor at 45 mm,
    850 nm, u = 1.2 m; 34 px per cell."""
    cam = pinmask.Camera(object_distance_m=1.2, lens_focal_m=0.075, sensor_distance_m=0.045,
                         wavelength_m=850e-9, pixel_pitch_m=5.86e-6, pinhole_m=300e-6,
                         sensor_cols=1920, sensor_rows=1200)
    cam.pinhole_m = 34 * cam.pixel_pitch_m / cr.m_u(cam)
    return cam, 34


# name: (camera, rows, cols, tiles, dark frame given, photons through a design pinhole)
SETUPS = {
    "phone-crop-1024": (phone, 1024, 1024, 16, True, 3e5),
    "phone-full": (phone, 3024, 4032, 16, False, 3e5),
    "nir-crop-512": (nir, 512, 512, 4, True, 3e5),
    "nir-crop-340": (nir, 340, 340, 4, True, 3e5),
}
BACKGROUND = 20.0


def make_setup(name):
    """(mask, noiseless capture, missing cells, truth, whether a dark frame is given)."""
    cam_of, rows, cols, tiles, dark, flux = SETUPS[name]
    cam, ppc = cam_of(rows, cols)
    mask = pinmask.generate(family="random", grid=10, holes=14, spacing=2, tiles=tiles, seed=5,
                            camera=cam, pixels_per_cell=ppc)
    # One blocked pinhole near the frame's centre.
    cells, x, y, _ = cr.spot_centres(mask, rows, cols, ROTATION, PITCH_SCALE)
    k = int(np.argmin((x - cols / 2) ** 2 + (y - rows / 2) ** 2))
    missing = {cells[k]}
    clean = cr.spots(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, missing, flux)
    clean += cr.film_leak(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, OD, flux)
    truth = {"rotation_deg": ROTATION, "pitch_px": ppc * PITCH_SCALE,
             "side_scale": SIDE_SCALE,
             "optical_density": cr.od_by_definition(OD, PITCH_SCALE, SIDE_SCALE)}
    return mask, clean, missing, truth, dark


def errors_in_sigmas(mask, clean, missing, truth, dark, seed):
    """Each parameter's (error, stated sigma) for one noise seed."""
    point = cr.noisy(clean, seed, background=BACKGROUND)
    r = pinmask.calibrate(point, mask, dark=np.full(clean.shape, BACKGROUND) if dark else None)
    assert {tuple(c) for c in r["missing_pinholes"]} == missing
    return {
        "rotation": (r["rotation_deg"] - truth["rotation_deg"], r["rotation_sigma_deg"]),
        "pitch x": (r["pitch_px"][0] - truth["pitch_px"], r["pitch_sigma_px"][0]),
        "pitch y": (r["pitch_px"][1] - truth["pitch_px"], r["pitch_sigma_px"][1]),
        "side": (r["pinhole_side_scale"] - truth["side_scale"], r["pinhole_side_scale_sigma"]),
        "OD": (r["optical_density"] - truth["optical_density"], r["optical_density_sigma"]),
    }


def coverage(name, seeds):
    """{parameter: (fraction of seeds whose 1-sigma interval holds the truth, mean error / rms
    sigma, spread of the errors / rms sigma)}."""
    setup = make_setup(name)
    runs = [errors_in_sigmas(*setup, seed) for seed in seeds]
    out = {}
    for p in runs[0]:
        e = np.array([run[p][0] for run in runs])
        s = np.array([run[p][1] for run in runs])
        rms = np.sqrt(np.mean(s ** 2))
        out[p] = (float(np.mean(np.abs(e) <= s)), float(np.mean(e) / rms),
                  float(np.std(e, ddof=1) / rms))
    return out


def test_renderer_spot_matches_direct_quadrature():
    """The Fourier-domain spot against the spot integrated over the pixels directly (the
    quadrature profile at 8 x 8 sub-samples, rotated; a fabricated side s passes s^2 of the
    design's flux), on the phone camera at 0.8 degrees."""
    cam, _ = phone(0, 0)

    class One:
        camera = cam

        class pattern:
            n, tiles_rows, tiles_cols, pinholes = 1, 1, 1, [(0, 0)]

    size = 41
    img = cr.spots(One, size, size, ROTATION, 1.0, SIDE_SCALE, (), 1.0, pad=1024)
    d = cam.pinhole_m * SIDE_SCALE
    a = d * cam.pixel_pitch_m / (cam.wavelength_m * cam.sensor_distance_m)
    inv_z = abs(1 / cam.sensor_distance_m - 1 / cam.lens_focal_m + 1 / cam.object_distance_m)
    n_f = d * d * inv_z / (4 * cam.wavelength_m)
    t = np.deg2rad(ROTATION)
    sub = (np.arange(8) + 0.5) / 8 - 0.5
    rows = [0, 7, 20]
    for r in rows:
        dy = (r + sub - (size - 1) / 2)[:, None, None]
        dx = (np.arange(size)[None, :, None] + sub[None, None, :] - (size - 1) / 2)
        u = np.cos(t) * dx - np.sin(t) * dy
        v = np.sin(t) * dx + np.cos(t) * dy
        k = cr.profile(u.ravel(), a, n_f) * cr.profile(v.ravel(), a, n_f)
        direct = SIDE_SCALE ** 2 * k.reshape(8, size, 8).mean(axis=(0, 2))
        assert np.allclose(img[r], direct, rtol=2e-3, atol=1e-4 * direct.max()), r


def test_coverage_on_a_small_crop():
    """Ten seeds on the NIR camera's 340 x 340 crop: every parameter's 1-sigma interval holds
    the truth in 4 to 10 of them (68 % expected; 3 or fewer has probability 1 % when the
    intervals are honest), and the errors' spread is within a factor two of the stated sigma."""
    for p, (c, bias, spread) in coverage("nir-crop-340", range(1, 11)).items():
        assert 0.4 <= c, (p, c, bias, spread)
        assert 0.5 <= spread <= 2.0, (p, c, bias, spread)


def test_noiseless_rotated_capture_is_fitted_to_its_truth():
    """The model against the renderer without noise, on the phone camera's 256 x 256 crop of a
    mask tiled 4 x 4 at 0.8 degrees: the fit's pinhole side within 1e-5 of the truth (the noisy
    fit's stated sigma here is 1.3e-4), rotation within 5e-6 deg, pitches within 1e-5 px, optical
    density within 0.005 (measured: 1.8e-6, 1.6e-6 deg, 3e-7 px, 7e-5). With each halo site on
    its nearest node, a bilinear read and the cores of cells beyond the fitted ones left out
    (docs/calibration.md) the side came out 6.2e-5 small and a pitch 1.1e-5 px large here."""
    cam, ppc = phone(0, 0)
    mask = pinmask.generate(family="random", grid=10, holes=14, spacing=2, tiles=4, seed=5,
                            camera=cam, pixels_per_cell=ppc)
    rows = cols = 256
    cells, x, y, _ = cr.spot_centres(mask, rows, cols, ROTATION, PITCH_SCALE)
    missing = {cells[int(np.argmin((x - cols / 2) ** 2 + (y - rows / 2) ** 2))]}
    clean = cr.spots(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, missing, 3e5)
    clean += cr.film_leak(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, OD, 3e5)
    r = pinmask.calibrate(clean + BACKGROUND, mask, dark=np.full(clean.shape, BACKGROUND))
    assert {tuple(c) for c in r["missing_pinholes"]} == missing
    assert abs(r["pinhole_side_scale"] - SIDE_SCALE) <= 1e-5, r["pinhole_side_scale"]
    assert abs(r["rotation_deg"] - ROTATION) <= 5e-6, r["rotation_deg"]
    for p in r["pitch_px"]:
        assert abs(p - ppc * PITCH_SCALE) <= 1e-5, r["pitch_px"]
    od = cr.od_by_definition(OD, PITCH_SCALE, SIDE_SCALE)
    assert abs(r["optical_density"] - od) <= 0.005, (r["optical_density"], od)


def cramer_rao(mask, rows, cols, missing, flux):
    """The Cramer-Rao standard errors of (rotation in degrees, pitch x and y in pixels, side
    scale, optical density) from the renderer's own Fisher information J^T diag(1 / var) J:
    parameters the mask's shift (x, y), rotation, pitch scales along the mask's columns and rows,
    side scale, one flux per spot whose centre lies within 2.5 cells of the frame (calibrate's
    fitted spots; farther ones fixed) and the film's leak; J by central differences of the
    renderer (single pad of 256 px, its wrap-around a smooth pedestal that moves with nothing),
    var the Poisson-Gaussian variance of the capture (the spots + leak + background, plus 3^2).
    The leak's image enters as a fixed shape times its amplitude (its dependence on the geometry,
    a thousandth of a pinhole per cell, is left out)."""
    cam, pat = mask.camera, mask.pattern
    _, x, y, pitch = cr.spot_centres(mask, rows, cols, ROTATION, PITCH_SCALE)
    cells = cr.spot_centres(mask, rows, cols, ROTATION, PITCH_SCALE)[0]
    reach = 2.5 * pitch
    free = [c for c, xi, yi in zip(cells, x, y)
            if -reach < xi < cols - 1 + reach and -reach < yi < rows - 1 + reach
            and c not in missing]
    geom = np.array([0.0, 0.0, ROTATION, PITCH_SCALE, PITCH_SCALE, SIDE_SCALE])

    def render(g, keep=None):
        others = set(missing) if keep is None else {c for c in cells if c != keep}
        return cr.spots_padded(mask, rows, cols, g[2], (g[3], g[4]), g[5], others, flux, None,
                               (g[0], g[1]), 256)

    steps = [1e-3, 1e-3, 1e-3, 1e-6, 1e-6, 1e-5]
    cols_j = []
    for i, h in enumerate(steps):
        up, down = geom.copy(), geom.copy()
        up[i] += h
        down[i] -= h
        cols_j.append((render(up) - render(down)) / (2 * h))
    for c in free:  # d m / d (spot flux), per unit of its true flux
        cols_j.append(render(geom, keep=c))
    leak = cr.film_leak(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, OD, flux)
    cols_j.append(leak)  # d m / d (leak amplitude), per unit of its true amplitude
    var = render(geom) + leak + BACKGROUND + 9.0
    J = np.stack([c.ravel() for c in cols_j], axis=1)
    fisher = J.T @ (J / var.ravel()[:, None])
    cov = np.linalg.inv(fisher)
    sd = np.sqrt(np.diag(cov))
    return {"rotation": sd[2], "pitch x": sd[3] * pitch / PITCH_SCALE,
            "pitch y": sd[4] * pitch / PITCH_SCALE, "side": sd[5],
            "OD": sd[-1] / np.log(10.0)}


def test_stated_sigmas_match_the_renderers_cramer_rao_bound():
    """calibrate's standard errors (the inverse Fisher information of its own model, scaled by
    the reduced chi^2) against the Cramer-Rao bound computed from the numpy renderer alone, on
    the NIR camera's 340 x 340 crop, seed 1: rotation, pitches and side within 10 % (measured:
    1.04, 1.04, 1.07, 1.07). A wrong derivative, a missing correlation with the spots' fluxes or
    a wrong scaling shows here. The optical density's stated sigma is 0.82 of its bound
    (docs/calibration.md: the fit's flux columns hold each spot's core, not its tails, which
    resemble the leak), so it is held only to 0.75 - 1.1 here."""
    cam_of, rows, cols, tiles, dark, flux = SETUPS["nir-crop-340"]
    mask, clean, missing, truth, dark = make_setup("nir-crop-340")
    bound = cramer_rao(mask, rows, cols, missing, flux)
    stated = {p: s for p, (e, s) in errors_in_sigmas(mask, clean, missing, truth, dark,
                                                      1).items()}
    for p in ["rotation", "pitch x", "pitch y", "side"]:
        assert 0.9 <= stated[p] / bound[p] <= 1.1, (p, stated[p], bound[p])
    assert 0.75 <= stated["OD"] / bound["OD"] <= 1.1, (stated["OD"], bound["OD"])


@pytest.mark.skipif(os.environ.get("PINMASK_SLOW") != "1",
                    reason="the coverage measurement (50 seeds, three setups: minutes); "
                           "run scripts/calibrate-coverage")
@pytest.mark.parametrize("name", ["phone-full", "phone-crop-1024", "nir-crop-512"])
def test_coverage_slow(name):
    cov = coverage(name, range(1, 51))
    for p, (c, bias, spread) in cov.items():
        print(name, p, c, bias, spread)
        assert 0.58 <= c <= 0.78, (name, p, c, bias, spread)


def band(centre, fwhm):
    """The light's spectrum as samples: a Gaussian of this FWHM at 13 wavelengths centre + k
    fwhm / 4, k = -6..6, weights summing to 1."""
    sigma = fwhm / (2 * np.sqrt(2 * np.log(2)))
    lam = centre + np.arange(-6, 7) * fwhm / 4
    w = np.exp(-((lam - centre) ** 2) / (2 * sigma ** 2))
    return list(zip(lam, w / w.sum()))


def band_errors(fwhm, seeds):
    """Errors in stated sigmas of calibrate on the NIR crop lit by a band of this FWHM (the
    mask's camera carrying the band), and the results of the first seed."""
    cam_of, rows, cols, tiles, dark, flux = SETUPS["nir-crop-340"]
    cam, ppc = cam_of(rows, cols)
    cam.bandwidth_m = fwhm
    mask = pinmask.generate(family="random", grid=10, holes=14, spacing=2, tiles=tiles, seed=5,
                            camera=cam, pixels_per_cell=ppc)
    cells, x, y, _ = cr.spot_centres(mask, rows, cols, ROTATION, PITCH_SCALE)
    missing = {cells[int(np.argmin((x - cols / 2) ** 2 + (y - rows / 2) ** 2))]}
    clean = cr.spots(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, missing, flux,
                     wavelengths=band(cam.wavelength_m, fwhm) if fwhm > 0 else None)
    clean += cr.film_leak(mask, rows, cols, ROTATION, PITCH_SCALE, SIDE_SCALE, OD, flux)
    truth = {"rotation_deg": ROTATION, "pitch_px": ppc * PITCH_SCALE, "side_scale": SIDE_SCALE,
             "optical_density": cr.od_by_definition(OD, PITCH_SCALE, SIDE_SCALE)}
    runs = [errors_in_sigmas(mask, clean, missing, truth, True, s) for s in seeds]
    first = pinmask.calibrate(cr.noisy(clean, seeds[0], BACKGROUND), mask,
                              dark=np.full(clean.shape, BACKGROUND))
    return {p: np.mean([r[p][0] / r[p][1] for r in runs]) for p in runs[0]}, first


def test_a_band_is_fitted_at_its_centre():
    """A camera with a band is calibrated, not refused: at the band's centre, which the results
    say. Measured with 4 seeds (docs/calibration.md): a 50 nm band at 850 nm (NIR crop, 0.8 deg)
    moves no parameter's mean error by more than 0.4 sigma; with 2 seeds here each stays within
    1.5 sigma."""
    errs, first = band_errors(50e-9, [1, 2])
    assert first["band"].startswith("fitted at the band's centre 850 nm"), first["band"]
    assert "50 nm" in first["band"], first["band"]
    for p, e in errs.items():
        assert abs(e) <= 1.5, (p, e)
