"""Hostile inputs: every one is a ValueError naming the problem, never a crash or a hang."""
import numpy as np
import pytest

import pinmask


@pytest.mark.parametrize("call,pattern", [
    (lambda: pinmask.scene("letter-R", 0, 5), "scene size"),
    (lambda: pinmask.scene("natural", 200000, 200000), "memory bound"),
    (lambda: pinmask.decode(np.zeros((0, 0)), psf=np.ones((3, 3))), "empty"),
    (lambda: pinmask.decode(np.ones((4, 4)), psf=np.ones((8, 8))), "smaller than one period"),
    (lambda: pinmask.decode(np.ones((8, 8), dtype=complex), psf=np.ones((3, 3))), "real"),
    (lambda: pinmask.decode("abc", psf=np.ones((3, 3))), "capture"),
    (lambda: pinmask.decode(np.full((8, 8), np.inf), psf=np.ones((3, 3))), "capture"),
    (lambda: pinmask.decode(np.ones((8, 8)), psf=np.full((3, 3), 1e308)),
     "beyond the double range"),
    (lambda: pinmask.decode(np.ones((8, 8)), psf=np.ones((3, 3)), method="tv", iters=-1),
     "--iters"),
    (lambda: pinmask.search(threads=0, evals=5), "threads"),
    (lambda: pinmask.search(time="-3s"), "--time|time"),
    (lambda: pinmask.simulate(pinmask.generate(), full_sensor=True, sensor=(0, 5)), "sensor"),
    (lambda: pinmask.Camera(sensor_cols=-5), "sensor"),
    (lambda: pinmask.Camera(wavelength_m=float("nan")), "wavelength_m"),
    (lambda: pinmask.mask_from_json('{"format": '), "mask JSON"),
    (lambda: pinmask.mask_from_json('{"format": "pinmask-mask", "format": "x"}'), "format"),
    (lambda: pinmask.generate(grid=5000, holes=1), "5000"),
    (lambda: pinmask.generate(attempts=0), "--attempts"),
    (lambda: pinmask.generate(pixels_per_cell=60000), "--pixels-per-cell"),
    (lambda: pinmask.Pattern(n=4, pinholes=[(9, 9)]).validate(), "outside"),
    (lambda: pinmask.sidelobes(pinmask.Pattern(n=4, pinholes=[])), "pinhole"),
    (lambda: pinmask.layout(pinmask.generate(), frame="-1mm"), "frame"),
    (lambda: pinmask.export_mask(pinmask.generate(), ""), "-o"),
    (lambda: pinmask.load_mask("/nonexistent/x.mask.json"), "cannot read"),
    (lambda: pinmask.read_psf("/nonexistent/p.tiff"), "p.tiff"),
    (lambda: pinmask.write_image("/tmp/x.bmp", np.zeros((3, 3))), "bmp|extension"),
])
def test_bad_input_is_value_error(call, pattern):
    with pytest.raises(ValueError, match=pattern):
        call()


def test_runtime_failure_is_runtime_error(tmp_path):
    # A valid request that fails while working (the output folder vanished): RuntimeError
    # (exit 1 on the command line), not ValueError.
    m = pinmask.generate()
    with pytest.raises((RuntimeError, ValueError)) as e:
        m.save(str(tmp_path / "no-such-dir" / "m.mask.json"))
    assert "no-such-dir" in str(e.value)


def test_bad_psf_files_same_message_as_cli(cli, bad_inputs, tmp_path):
    pinmask.write_image(str(tmp_path / "cap.npy"), np.ones((64, 64)))
    for name in ["psf-nan.tiff", "psf-zero.npy", "psf-overflow.npy", "psf-sidecar-version.tiff",
                 "psf-sidecar-size.tiff"]:
        path = str(bad_inputs / name)
        msg = cli.error("decode", "cap.npy", "--psf", path, "-o", "x.npy")
        with pytest.raises(ValueError) as e:
            pinmask.read_psf(path)
        assert str(e.value) == msg, name


def test_a_raw_file_that_crashes_libraw_is_a_value_error(cli, source_dir, tmp_path):
    # Debian 12's LibRaw 0.20.2 aborts on this DNG (make "Hasselblad", a 63-character model):
    # core/raw_io runs LibRaw in a child process, so the interpreter survives and gets the same
    # message as the command line. A LibRaw without the bug reads it like any DNG.
    path = source_dir / "fuzz" / "corpus" / "raw" / "hasselblad-long-model.dng"
    try:
        image, _ = pinmask.read_image(str(path))
    except ValueError as e:
        assert "LibRaw crashed reading this file" in str(e)
        pinmask.write_image(str(tmp_path / "psf.npy"), np.ones((8, 8)))
        assert cli.error("decode", str(path), "--psf", "psf.npy", "-o", "x.npy") == str(e)
    else:
        assert image.shape == (12, 16)
    # The module still works afterwards.
    image, _ = pinmask.read_image(str(source_dir / "fuzz" / "corpus" / "raw" / "small.dng"))
    assert image.shape == (12, 16)
