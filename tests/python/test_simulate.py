"""Simulation: the module against `pinmask simulate` (same seed, same numbers)."""
import numpy as np
import pytest

import pinmask


def test_simulate_gaussian_equals_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "letter-R", "--snr", "30", "--seed", "1",
            "-o", "cap.npy")
    s = pinmask.simulate(mask7, "letter-R", snr_db=30, seed=1)
    assert np.array_equal(s["capture"].astype(np.float32), np.load(tmp_path / "cap.npy"))


def test_simulate_photon_dark_frame_equals_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "usaf", "--photons", "500", "--read-noise",
            "3", "--dark-current", "2", "--optical-density", "3", "--full-well", "20000",
            "--bits", "12", "--seed", "4", "-o", "cap.npy", "--dark-frame", "dark.npy")
    s = pinmask.simulate(mask7, "usaf", photons=500, read_noise=3, dark_current=2,
                         optical_density=3, full_well=20000, bits=12, seed=4, dark_frame=True)
    assert np.array_equal(s["capture"].astype(np.float32), np.load(tmp_path / "cap.npy"))
    assert np.array_equal(s["dark"].astype(np.float32), np.load(tmp_path / "dark.npy"))
    assert s["background"][0] > 0


def test_simulate_full_sensor_is_the_periodic_extension(mask7):
    s = pinmask.simulate(mask7, "letter-R", snr_db=float("inf"), full_sensor=True,
                         sensor=(300, 200))
    cap, clean = s["capture"], s["clean"]
    assert cap.shape == (200, 300)
    assert np.array_equal(cap, clean)  # noiseless
    r0, c0 = s["origin"]
    period = pinmask.simulate(mask7, "letter-R", snr_db=float("inf"))["capture"]
    rows = (np.arange(200) - r0) % 128
    cols = (np.arange(300) - c0) % 128
    assert np.array_equal(cap, period[np.ix_(rows, cols)])


def test_simulate_noiseless_is_circular_convolution(mask7):
    """Independent reference: the capture is scene (*) PSF with the PSF's centre at zero shift."""
    s = pinmask.simulate(mask7, "letter-R", snr_db=float("inf"))
    scene = pinmask.scene("letter-R", 128, 128)
    psf = s["psf"]
    centred = np.roll(psf, (-64, -64), axis=(0, 1))
    ref = np.real(np.fft.ifft2(np.fft.fft2(scene) * np.fft.fft2(centred)))
    assert np.max(np.abs(s["capture"] - ref)) < 1e-12  # FFT rounding only


def test_simulate_array_scene_and_bad_inputs(mask7):
    scene = np.zeros((128, 128), dtype=np.float32)
    scene[60:68, 60:68] = 1
    s = pinmask.simulate(mask7, scene, snr_db=float("inf"))
    assert s["capture"].sum() == pytest.approx(64.0, rel=1e-9)
    with pytest.raises(ValueError, match="^snr_db = 30: cannot be combined with photons"):
        pinmask.simulate(mask7, "letter-R", snr_db=30, photons=100)
    with pytest.raises(ValueError, match="^dark_frame = True: needs the photon model"):
        pinmask.simulate(mask7, "letter-R", dark_frame=True)
    with pytest.raises(ValueError, match="^read_noise: a sensor parameter"):
        pinmask.simulate(mask7, "letter-R", read_noise=2)


def test_unknown_scene_same_message_as_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    msg = cli.error("simulate", "m.mask.json", "--scene", "no-such-scene", "-o", "c.tiff")
    with pytest.raises(ValueError) as e:
        pinmask.simulate(mask7, "no-such-scene")
    assert str(e.value) == msg


def test_simulate_precision_matches_cli_and_double(cli, tmp_path, mask7):
    """precision: double is the default's bytes below 256 x 256; single equals the CLI's
    --precision single and stays within float rounding of double (the 5e-6 relative l2 bound
    of tests/optimize/simulate/test_simulate_precision.cpp); a bad name names the keyword."""
    mask7.save(str(tmp_path / "m.mask.json"))
    d = pinmask.simulate(mask7, "usaf", snr_db=30, seed=2)["capture"]
    assert np.array_equal(d, pinmask.simulate(mask7, "usaf", snr_db=30, seed=2,
                                              precision="double")["capture"])
    s = pinmask.simulate(mask7, "usaf", snr_db=30, seed=2, precision="single")["capture"]
    assert not np.array_equal(s, d)
    assert np.linalg.norm(s - d) <= 5e-6 * np.linalg.norm(d)
    cli.run("simulate", "m.mask.json", "--scene", "usaf", "--snr", "30", "--seed", "2",
            "--precision", "single", "-o", "cap.npy")
    assert np.array_equal(s.astype(np.float32), np.load(tmp_path / "cap.npy"))
    with pytest.raises(ValueError, match="^precision = half"):
        pinmask.simulate(mask7, precision="half")


def test_exact_geometry_capture_equals_cli(cli, tmp_path):
    """`simulate --geometry exact` on a camera that is not the paper's, refocused to 2 m: the
    same capture, noise included (same seed). The exact PSF's geometry is checked against
    Eq. (3) in test_psf.py."""
    cam = pinmask.Camera(pixel_pitch_m="5.86um", sensor_cols=640, sensor_rows=480,
                         lens_focal_m="75mm", sensor_distance_m="45mm",
                         object_distance_m="1.2m", wavelength_m="850nm", pinhole_m="120um")
    mask = pinmask.generate(camera=cam, grid=8, holes=6, seed=3)
    mask.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "point", "--geometry", "exact",
            "--object-distance", "2m", "--size", "200x240", "--snr", "40", "--seed", "2",
            "-o", "cap.npy")
    out = pinmask.simulate(mask, "point", snr_db=40, seed=2, geometry="exact",
                           object_distance="2m", size=(200, 240))
    ref = np.load(tmp_path / "cap.npy")
    assert out["capture"].shape == ref.shape == (200, 240)
    assert np.array_equal(out["capture"].astype(ref.dtype), ref)
    assert out["object_distance_m"] == 2.0 and out["psf"] is None
    with pytest.raises(ValueError, match="^size = 200x240: only used with geometry='exact'"):
        pinmask.simulate(mask, "point", size=(200, 240))


def test_exact_geometry_refusals_name_keywords():
    mask = pinmask.generate(seed=3)
    with pytest.raises(ValueError, match="^full_sensor = given: geometry='exact' always covers "
                                         "the sensor \\(or size ROWSxCOLS\\)"):
        pinmask.simulate(mask, "point", geometry="exact", full_sensor=True)
    with pytest.raises(ValueError, match="^object_distance = 2m: only used with "
                                         "geometry='exact'"):
        pinmask.simulate(mask, "point", object_distance="2m")


def test_simulate_threads_do_not_change_the_capture(mask7):
    # A 512 x 512 full-sensor capture (the size FFTW plans with threads): as `simulate
    # --threads`, the bytes do not depend on the count without a wisdom cache.
    a = pinmask.simulate(mask7, full_sensor=True, sensor=(512, 512), threads=1)["capture"]
    b = pinmask.simulate(mask7, full_sensor=True, sensor=(512, 512), threads=2)["capture"]
    assert np.array_equal(a, b)
    with pytest.raises(ValueError, match="threads = -1"):
        pinmask.simulate(mask7, threads=-1)
