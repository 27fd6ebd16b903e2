"""pinmask.calibrate and `pinmask calibrate`: a point-source capture rendered here with numpy
(the diffraction integral of a square pinhole by Gauss-Legendre quadrature, pixel-integrated by
sub-samples), rotated by scipy.ndimage.rotate (the convention's reference: a positive angle is
counter-clockwise on screen with rows running down), with Poisson photons and read noise. The
module and the command line must report the same results, and the rotation's sign must be
scipy's."""
import json
import subprocess

import numpy as np
import pytest
import scipy.ndimage as ndi

import pinmask


def pinhole_profile(fresnel_n, v):
    """Per-axis intensity density |J|^2 / 4, J = int_{-1}^{1} exp(i pi (N s^2 - v s)) ds."""
    s, w = np.polynomial.legendre.leggauss(400)
    phase = np.pi * (fresnel_n * s[None, :] ** 2 - np.asarray(v)[:, None] * s[None, :])
    j = (w[None, :] * np.exp(1j * phase)).sum(axis=1)
    return np.abs(j) ** 2 / 4


def point_source(mask, size, rotation_deg, missing=(), flux=60000.0, seed=1):
    cam = mask.camera
    inv_z = 1 / cam.sensor_distance_m - 1 / cam.lens_focal_m + 1 / cam.object_distance_m
    m_u = cam.sensor_distance_m * inv_z
    pitch = m_u * cam.pinhole_m / cam.pixel_pitch_m
    a = cam.pinhole_m * cam.pixel_pitch_m / (cam.wavelength_m * cam.sensor_distance_m)
    n_f = cam.pinhole_m ** 2 * abs(inv_z) / (4 * cam.wavelength_m)
    big = size + 100
    # Pixel-integrated 1-D profile at 8 sub-samples per pixel, as a function of the offset.
    sub = (np.arange(8) + 0.5) / 8 - 0.5
    pat = mask.pattern
    nt = pat.n * pat.tiles_rows
    centre = (big - 1) / 2
    img = np.zeros((big, big))
    x = np.arange(big)
    for tr in range(pat.tiles_rows):
        for tc in range(pat.tiles_cols):
            for (r, c) in pat.pinholes:
                cell = (r + tr * pat.n, c + tc * pat.n)
                if cell in missing:
                    continue
                cy = centre + (cell[0] + 0.5 - nt / 2) * pitch
                cx = centre + (cell[1] + 0.5 - nt / 2) * pitch
                off_x = (x[:, None] + sub[None, :] - cx).ravel()
                off_y = (x[:, None] + sub[None, :] - cy).ravel()
                px = (a * pinhole_profile(n_f, a * off_x)).reshape(big, 8).mean(axis=1)
                py = (a * pinhole_profile(n_f, a * off_y)).reshape(big, 8).mean(axis=1)
                img += flux * np.outer(py, px)
    img = ndi.rotate(img, rotation_deg, reshape=False, order=3)
    lo = (big - size) // 2
    img = img[lo:lo + size, lo:lo + size]
    rng = np.random.default_rng(seed)
    counts = rng.poisson(np.clip(img + 20.0, 0, None)) + rng.normal(0, 3.0, img.shape)
    return np.round(counts), pitch


@pytest.fixture(scope="module")
def capture():
    mask = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=7)
    missing = {(mask.pattern.pinholes[3][0], mask.pattern.pinholes[3][1] + 16)}
    point, pitch = point_source(mask, 200, 1.0, missing=missing)
    return mask, point, pitch, missing


def test_rotation_sign_is_scipy_ndimage_rotate(capture):
    mask, point, pitch, missing = capture
    r = pinmask.calibrate(point, mask)
    assert r["rotation_deg"] == pytest.approx(1.0, abs=max(4 * r["rotation_sigma_deg"], 0.02))
    assert r["rotation_deg"] > 0.9
    assert "counter-clockwise" in r["rotation_convention"]
    for p in r["pitch_px"]:
        assert p == pytest.approx(pitch, rel=2e-3)
    assert {tuple(c) for c in r["missing_pinholes"]} == missing
    assert r["psf"].shape == point.shape
    assert r["psf"].sum() == pytest.approx(1.0)
    assert r["optical_density"] is None or r["optical_density"] >= 0


def same(a, b):
    """JSON value a against the module's value b (tuples as lists), floats to 1e-12."""
    if isinstance(b, (tuple, list)):
        return isinstance(a, list) and len(a) == len(b) and all(map(same, a, b))
    if isinstance(b, dict):
        return isinstance(a, dict) and set(a) == set(b) and all(same(a[k], b[k]) for k in b)
    if isinstance(b, float) and isinstance(a, (int, float)):
        return a == pytest.approx(b, rel=1e-12, abs=1e-300)
    return a == b


def test_module_returns_the_command_lines_json(capture, cli, tmp_path):
    mask, point, pitch, missing = capture
    mask.save(tmp_path / "m.mask.json")
    np.save(tmp_path / "point.npy", point)
    out = cli.run("calibrate", tmp_path / "point.npy", "--mask", tmp_path / "m.mask.json",
                  "-o", tmp_path / "cal", "--json")
    j = json.loads(out.stdout)
    # Progress with stderr to a pipe: each phase named, then the fit's iterations.
    for phase in ["finding the lattice (FFT)", "fitting the forward model",
                  "building the calibrated PSF"]:
        assert f"pinmask calibrate: {phase}" in out.stderr, out.stderr
    assert "iterations" in out.stderr, out.stderr
    r = pinmask.calibrate(point, tmp_path / "m.mask.json")
    files = {"psf", "psf_period", "kernel", "mask", "report"}
    assert set(j) - files == set(r) - files - {"residual_map"}
    # Messages name the face's own spelling: the flag --dark, the keyword dark.
    j["dark_source"] = j["dark_source"].replace("--dark", "dark")
    for key in sorted(set(j) - files):
        assert same(j[key], r[key]), (key, j[key], r[key])
    # One transaction, one rendering: the same values exactly, as plain containers.
    plain = r.to_dict()
    assert {k: plain[k] for k in set(j) - files} == {k: j[k] for k in set(j) - files}


def test_untrustworthy_capture_is_refused(capture):
    mask, point, pitch, missing = capture
    rng = np.random.default_rng(3)
    dim = np.round(rng.poisson(np.clip(point * 0.0005, 0, None) + 20.0)).astype(float)
    with pytest.raises(ValueError):
        pinmask.calibrate(dim, mask)


def test_command_under_a_file_size_limit_leaves_nothing(capture, cli, tmp_path):
    """`ulimit -f 8`: the write past 8 KiB fails (SIGXFSZ ignored); the command exits 1 naming
    the file and the reason, and leaves no file in its output folder."""
    mask, point, pitch, missing = capture
    mask.save(tmp_path / "m.mask.json")
    np.save(tmp_path / "point.npy", point)
    script = 'ulimit -f 8 && exec "$0" "$@"'
    p = subprocess.run(["bash", "-c", script, cli.exe, "calibrate", str(tmp_path / "point.npy"),
                        "--mask", str(tmp_path / "m.mask.json"), "-o", str(tmp_path / "cal")],
                       capture_output=True, text=True)
    assert p.returncode == 1, p.stderr
    assert "could not write '" + str(tmp_path / "cal") in p.stderr
    assert "File too large" in p.stderr
    left = [f for f in (tmp_path / "cal").rglob("*") if f.is_file()] if (
        tmp_path / "cal").exists() else []
    assert left == []
