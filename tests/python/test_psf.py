"""PSF: the module against `pinmask psf`, and the zero-copy contract of returned arrays."""
import numpy as np
import pytest

import pinmask


def test_psf_equals_cli_npy(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("psf", "m.mask.json", "-o", "psf.tiff", "--npy")
    cli_psf = np.load(tmp_path / "psf.npy")
    psf = pinmask.psf(mask7)
    assert psf.shape == cli_psf.shape == (128, 128)
    assert np.array_equal(psf.astype(np.float32), cli_psf)  # float32 file of the same doubles
    assert psf.sum() == pytest.approx(1.0, abs=1e-12)


def test_write_psf_same_bytes_as_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("psf", "m.mask.json", "-o", "cli.tiff", "--npy")
    (tmp_path / "py").mkdir()
    written = pinmask.write_psf(mask7, str(tmp_path / "py" / "cli.tiff"), npy=True,
                                mask_file="m.mask.json")
    assert len(written) == 3
    for name in ["cli.tiff", "cli.npy", "cli.json"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / name).read_bytes(), name


def test_read_psf_roundtrip(tmp_path, mask7):
    pinmask.write_psf(mask7, str(tmp_path / "p.tiff"), mask_file="x")
    psf, side = pinmask.read_psf(str(tmp_path / "p.tiff"))
    assert side["mask_geometry_hash"] == mask7.geometry_hash()
    assert side["size_px"] == (128, 128)
    ref = pinmask.psf(mask7)
    ref32 = ref.astype(np.float32).astype(np.float64)
    assert np.allclose(psf, ref32 / ref32.sum(), rtol=0, atol=1e-15)


def test_returned_array_owns_library_buffer(mask7):
    psf = pinmask.psf(mask7)
    assert psf.dtype == np.float64 and psf.flags.c_contiguous
    assert not psf.flags.owndata  # the buffer belongs to the library's Plane
    assert type(psf.base).__name__ == "PyCapsule"
    assert pinmask.is_library_buffer(psf)
    assert not pinmask.is_library_buffer(psf.copy())
    assert not pinmask.is_library_buffer(psf[1:, :])  # a view of part of it is not the plane
    assert not pinmask.is_library_buffer(psf.astype(np.float32))


def test_kernel_values_is_a_view(mask7):
    k = pinmask.kernel(mask7)
    v = k.values
    assert v.sum() == pytest.approx(1.0, abs=1e-12)
    assert k.model in ("fresnel", "box", "fraunhofer")
    assert np.shares_memory(v, k.values)  # two reads: the same buffer, no copies
    v[0, 0] = 42.0
    assert k.values[0, 0] == 42.0  # writing through the view reaches the kernel


def test_kernel_override_refused_like_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    msg = cli.error("psf", "m.mask.json", "-o", "p.tiff", "--kernel", "measured")
    with pytest.raises(ValueError) as e:
        pinmask.psf(mask7, kernel="measured")
    # The same message, naming the keywords where the CLI names its flags.
    assert msg == "--kernel = measured: needs --kernel-path FILE"
    assert str(e.value) == "kernel = measured: needs kernel_path FILE"


def test_image_io_roundtrip(tmp_path):
    img = np.linspace(0, 1, 12 * 7).reshape(12, 7)
    pinmask.write_image(str(tmp_path / "a.npy"), img)
    back, full_scale = pinmask.read_image(str(tmp_path / "a.npy"))
    assert full_scale == 1.0
    assert np.array_equal(back, img.astype(np.float32).astype(np.float64))
    rgb = np.random.default_rng(0).random((5, 6, 3))
    pinmask.write_image(str(tmp_path / "c.npy"), rgb)
    back, _ = pinmask.read_image(str(tmp_path / "c.npy"))
    assert back.shape == (5, 6, 3)
    assert np.allclose(back, rgb, atol=1e-7)


# Exact geometry (`pinmask psf --geometry exact`): a smaller NIR-like camera than the paper's
# (f = 45 mm, f' = 75 mm, w = 5.86 um), refocused to u = 2 m.
NIR = dict(pixel_pitch_m="5.86um", sensor_cols=640, sensor_rows=480, lens_focal_m="75mm",
           sensor_distance_m="45mm", object_distance_m="1.2m", wavelength_m="850nm",
           pinhole_m="350um")


def test_exact_psf_equals_cli_and_lands_where_eq3_puts_it(cli, tmp_path):
    # The box kernel: compact spots, none cut by the window, so the centroid is exact.
    mask = pinmask.generate(camera=pinmask.Camera(**NIR), grid=12, holes=9, seed=3, kernel="box")
    mask.save(str(tmp_path / "m.mask.json"))
    cli.run("psf", "m.mask.json", "-o", "e.tiff", "--npy", "--geometry", "exact",
            "--object-distance", "2m", "--size", "700x720")
    ref = np.load(tmp_path / "e.npy")
    got = pinmask.psf(mask, geometry="exact", object_distance="2m", size=(700, 720))
    assert got.shape == ref.shape == (700, 720)
    assert np.array_equal(got.astype(np.float32), ref)  # the CLI writes float32
    # Independent of pinmask: Eq. (3) puts each tiled pinhole's spot at
    # rows/2 + M(u) s / w with M(u) = 1 - f/f' + f/u; area resampling keeps each spot's
    # centroid there, so the PSF's centroid is their mean (every spot inside the window).
    f, fl, w, d, u = 0.045, 0.075, 5.86e-6, 350e-6, 2.0
    m_u = 1 - f / fl + f / u
    n, tiles = 12, 2
    nt = n * tiles
    centres = [((i + 0.5) - nt / 2) * d * m_u / w
               for (r, c) in mask.pattern.pinholes for t in range(tiles)
               for i in [r + t * n]]
    rows_expected = 700 / 2 + np.mean(centres)
    cols_centres = [((j + 0.5) - nt / 2) * d * m_u / w
                    for (r, c) in mask.pattern.pinholes for t in range(tiles) for j in [c + t * n]]
    cols_expected = 720 / 2 + np.mean(cols_centres)
    rr, cc = np.mgrid[0:700, 0:720] + 0.5  # pixel k covers [k, k + 1)
    assert abs((got * rr).sum() / got.sum() - rows_expected) < 0.05
    assert abs((got * cc).sum() / got.sum() - cols_expected) < 0.05
    assert abs(got.sum() - tiles * tiles) < 1e-6  # K spots of 1/K per tile, none cut


def test_exact_psf_keeps_spots_wider_than_the_period():
    # The walkthrough's NIR camera with a 120 um pinhole: 8.96 px per cell, so an 8 x 8 period is
    # 72 px while the spot's diffraction main lobe spans about 108 px. The cyclic PSF must fold
    # its kernel into the period; the exact-geometry PSF of one pinhole over a 400 x 400 frame
    # must not cut it there (it did, renormalised, moving light into the period).
    cam = pinmask.Camera(pixel_pitch_m="5.86um", sensor_cols=640, sensor_rows=480,
                         lens_focal_m="75mm", sensor_distance_m="45mm", object_distance_m="1.2m",
                         wavelength_m="850nm", pinhole_m="120um")
    mask = pinmask.generate(camera=cam, grid=8, holes=1, tiles=1, seed=1)
    period = 8 * mask.pixels_per_cell
    got = pinmask.psf(mask, geometry="exact", size=(400, 400))
    cols = np.nonzero(got.sum(axis=0) > 1e-6 * got.sum())[0]
    assert cols[-1] - cols[0] + 1 > period + 30
    # The light the period's window holds: the kernel's own share, not all of it.
    r, c = np.unravel_index(np.argmax(got), got.shape)
    inside = got[r - period // 2:r + period // 2, c - period // 2:c + period // 2].sum()
    assert inside < 0.97 * got.sum()
    # One spot of weight 1 (K = 1): the frame holds all but the far tails.
    assert 0.95 < got.sum() <= 1.0 + 1e-9


def test_exact_psf_settings_need_exact_geometry():
    mask = pinmask.generate(seed=3)
    with pytest.raises(ValueError, match="^object_distance = 2m: only used with geometry='exact'"):
        pinmask.psf(mask, object_distance="2m")
    with pytest.raises(ValueError, match="^geometry = 'straight'|^geometry = straight"):
        pinmask.psf(mask, geometry="straight")


@pytest.mark.parametrize("camera,u", [
    (NIR, 2.0), (NIR, 0.7),  # 25.23 and 27.73 px per cell
    ("paper", 3.0), ("paper", 1.3)])  # 8.21 and 8.57 px per cell
def test_exact_box_psf_matches_an_independent_model_at_fractional_pitch(tmp_path, camera, u):
    # The box kernel's spots follow u in size as well as position: each spot is the square of
    # side d |M(u)| / w pixels at its Eq. (3) centre, integrated exactly over the pixels. The
    # numpy model of depth_scenes.py (written for the tests, not pinmask's code) draws the same,
    # so away from whole-pixel pitches the two must agree to rounding (area resampling of a
    # kernel built at the mask's whole pixels per cell blurred each spot by up to a pixel).
    import pathlib
    import sys
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    import depth_scenes as ds
    cam = pinmask.Camera(**NIR) if camera == NIR else pinmask.paper_camera()
    mask = pinmask.generate(camera=cam, grid=12, holes=9, tiles=2, seed=5, kernel="box")
    mask.save(str(tmp_path / "m.mask.json"))
    mj = ds.load(tmp_path / "m.mask.json")
    o = mj["optics"]
    pitch = o["pinhole_m"] * ds.magnification(o, u) / o["pixel_pitch_m"]
    assert abs(pitch - round(pitch)) > 0.2  # a fractional pitch: not the integer model's case
    size = (700, 720) if camera == NIR else (260, 270)  # every spot inside the window
    got = pinmask.psf(mask, geometry="exact", object_distance=f"{u}m", size=size)
    ref = ds.exact_psf(mj, u, *size)
    assert got.shape == ref.shape
    assert abs(ref.sum() - 4) < 1e-9  # 2 x 2 tiles of K spots of 1/K, none cut
    assert np.max(np.abs(got - ref)) <= 1e-12 * np.max(ref)
