"""Hostile inputs: every one is a ValueError naming the problem, never a crash or a hang."""
import re

import numpy as np
import pytest

import pinmask


@pytest.mark.parametrize("call,pattern", [
    (lambda: pinmask.scene("letter-R", 0, 5), "scene size"),
    (lambda: pinmask.scene("natural", 200000, 200000), "memory bound"),
    (lambda: pinmask.decode(np.zeros((0, 0)), psf=np.ones((3, 3))), "empty"),
    (lambda: pinmask.decode(np.ones((4, 4)), psf=np.ones((8, 8)), model="cyclic"),
     "smaller than one period"),
    (lambda: pinmask.decode(np.ones((8, 8), dtype=complex), psf=np.ones((3, 3))), "real"),
    (lambda: pinmask.decode(np.full((8, 8), np.inf), psf=np.ones((3, 3))), "capture"),
    (lambda: pinmask.decode(np.ones((8, 8)), psf=np.full((3, 3), 1e308)),
     "beyond the double range"),
    (lambda: pinmask.decode(np.ones((8, 8)), psf=np.ones((3, 3)), method="tv", iters=-1),
     "^iters = -1"),
    (lambda: pinmask.search(threads=0, evals=5), "threads"),
    (lambda: pinmask.search(time="-3s"), "time"),
    # The command line's bounds hold here too (the libraries define them once).
    (lambda: pinmask.search(evals=10**12), "^evals = 1000000000000: must be 0"),
    (lambda: pinmask.search(evals=5, top=1001), "^top = 1001"),
    (lambda: pinmask.simulated_quality(pinmask.generate(), noise_seeds=10**9),
     "^noise_seeds = 1000000000: must be between 1 and 1000"),
    (lambda: pinmask.simulate(pinmask.generate(), full_sensor=True, sensor=(0, 5)), "sensor"),
    (lambda: pinmask.Camera(sensor_cols=-5), "sensor"),
    (lambda: pinmask.Camera(wavelength_m=float("nan")), "wavelength_m"),
    (lambda: pinmask.mask_from_json('{"format": '), "mask JSON"),
    (lambda: pinmask.mask_from_json('{"format": "pinmask-mask", "format": "x"}'), "format"),
    (lambda: pinmask.generate(grid=5000, holes=1), "5000"),
    (lambda: pinmask.generate(attempts=0), "^attempts = 0"),
    (lambda: pinmask.generate(pixels_per_cell=60000), "^pixels_per_cell = 60000"),
    (lambda: pinmask.Pattern(n=4, pinholes=[(9, 9)]).validate(), "outside"),
    (lambda: pinmask.sidelobes(pinmask.Pattern(n=4, pinholes=[])), "pinhole"),
    (lambda: pinmask.layout(pinmask.generate(), frame="-1mm"), "frame"),
    (lambda: pinmask.export_mask(pinmask.generate(), ""), "^out_dir = ''"),
    (lambda: pinmask.load_mask("/nonexistent/x.mask.json"), "cannot read"),
    (lambda: pinmask.read_psf("/nonexistent/p.tiff"), "p.tiff"),
    (lambda: pinmask.write_image("/tmp/x.bmp", np.zeros((3, 3))), "bmp|extension"),
])
def test_bad_input_is_value_error(call, pattern):
    with pytest.raises(ValueError, match=pattern):
        call()


@pytest.mark.parametrize("call,keyword,flag", [
    (lambda: pinmask.decode(np.ones((8, 8)), psf=np.ones((3, 3)), method="tv", iters=0),
     "iters", "--iters"),
    (lambda: pinmask.search(evals=5, filter="nsr:-1"), "filter", "--filter"),
    (lambda: pinmask.search(evals=5, objective="robust-filter"), "objective", "--objective"),
    (lambda: pinmask.metrics(pinmask.generate(), robust="size=-1um"), "robust size",
     "--robust"),
    (lambda: pinmask.metrics(pinmask.generate(), prior_scenes=0), "prior_scenes",
     "--prior-scenes"),
    (lambda: pinmask.metrics(pinmask.generate(), nsr="-1"), "nsr", "--nsr"),
    (lambda: pinmask.simulate(pinmask.generate(), read_noise=2), "read_noise", "--read-noise"),
    (lambda: pinmask.simulate(pinmask.generate(), photons=100, bits=8), "full_well",
     "--full-well"),
    (lambda: pinmask.layout(pinmask.generate(), chord_tol="-1um"), "chord_tol", "--chord-tol"),
    # export_mask checks its settings before it creates the output folder.
    (lambda: pinmask.export_mask(pinmask.generate(), "/nonexistent/fab", shape="polygon",
                                 sides=2), "sides", "--sides"),
    (lambda: pinmask.export_mask(pinmask.generate(), "/nonexistent/fab", dpi=0), "dpi",
     "--dpi"),
    (lambda: pinmask.export_mask(pinmask.generate(), "/nonexistent/fab", formats=["oasis2"]),
     "formats", "--format"),
])
def test_a_bad_keyword_value_names_the_keyword(call, keyword, flag):
    # The libraries name the setting by its field (core/errors/field_names.hpp); the module spells it
    # as its keyword argument (python/keyword_names.cpp), never as the command-line flag.
    with pytest.raises(ValueError) as e:
        call()
    assert keyword in str(e.value)
    assert flag not in str(e.value)
    assert "`" not in str(e.value)  # every field reference was spelled


def test_keyword_table_is_sorted_and_names_keywords(source_dir):
    # python/keyword_names.cpp: field -> keyword, sorted by field (looked up by binary search),
    # each keyword a parameter of some function of the module (or its value, "rerank_tv=False").
    text = (source_dir / "python" / "keyword_names.cpp").read_text()
    rows = re.findall(r'\{"([^"]+)", "([^"]+)"\},', text)
    assert len(rows) > 0
    fields = [f for f, _ in rows]
    assert fields == sorted(fields, key=lambda f: f.encode()) and len(set(fields)) == len(fields)
    stub = (source_dir / "python" / "pinmask.pyi").read_text()
    for field, keyword in rows:
        name = keyword.split("=")[0]
        assert re.search(r"\b" + re.escape(name) + r"\s*:", stub), (field, keyword)


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
    # core/image/raw_io runs LibRaw in a child process, so the interpreter survives and gets the same
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
