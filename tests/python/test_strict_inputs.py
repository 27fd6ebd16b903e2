"""Python as strict as the command line: wrong dtypes and wrong types are TypeErrors in the
module's words (never pybind11's "Unable to cast"), lengths with units read as the command line
reads them, arrays charged to the memory budget from their shape before any copy, the library's
caps met by both faces, and the file-size limit reported without killing the interpreter."""
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import pinmask


@pytest.fixture(scope="module")
def mask7():
    return pinmask.generate(grid=7, holes=5, tiles=1, seed=1)


@pytest.mark.parametrize("dtype", [bool, "U4", object])
def test_non_numeric_captures_are_type_errors(mask7, dtype):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"] > 0.5
    with pytest.raises(TypeError) as e:
        pinmask.decode(cap.astype(dtype), mask=mask7)
    assert "is not an image" in str(e.value) and "Unable to cast" not in str(e.value)


def test_a_string_is_not_a_capture():
    with pytest.raises(TypeError, match="capture: an array of dtype <U3 is not an image"):
        pinmask.decode("abc", psf=np.ones((3, 3)))


def test_bool_capture_refused_by_calibrate(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    with pytest.raises(TypeError, match="dtype bool is not an image"):
        pinmask.calibrate(cap > cap.mean(), mask=mask7)


def test_fortran_order_equals_c_order(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    a = pinmask.decode(np.ascontiguousarray(cap), mask=mask7)["image"]
    b = pinmask.decode(np.asfortranarray(cap), mask=mask7)["image"]
    assert np.array_equal(a, b)


def test_views_are_charged_from_their_shape():
    # A 200000 x 200000 broadcast view owns 8 bytes; its float64 copy would take 320 GB.
    view = np.broadcast_to(np.float32(1.0), (200000, 200000))
    with pytest.raises(ValueError) as e:
        pinmask.decode(view, psf=np.ones((8, 8)))
    assert "memory bound" in str(e.value) and "capture" in str(e.value)


def test_lengths_with_units_read_like_the_command_line(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    kw = dict(mask=mask7, steps=3, window=5, smooth=0)
    a = pinmask.depthmap(cap, from_m=0.4, to_m=2.0, **kw)
    b = pinmask.depthmap(cap, from_m="40cm", to_m="2m", **kw)
    assert np.array_equal(a["depth_m"], b["depth_m"])
    with pytest.raises(ValueError, match="from_m"):
        pinmask.depthmap(cap, from_m="40 parsecs", to_m="2m", **kw)
    with pytest.raises(TypeError) as e:
        pinmask.depthmap(cap, from_m=[0.4], to_m="2m", **kw)
    assert "from_m" in str(e.value) and "Unable to cast" not in str(e.value)
    with pytest.raises(TypeError, match="from_m"):
        pinmask.depthmap(cap, from_m=True, to_m="2m", **kw)


def test_prior_scene_count_capped_in_the_library(mask7):
    with pytest.raises(ValueError) as e:
        pinmask.analytic_error(mask7, prior_scenes=10**9)
    assert "prior_scenes = 1000000000: must be between 1 and 4096" in str(e.value)


def test_search_time_capped_in_the_library():
    with pytest.raises(ValueError, match="time = .*must be between 0 and 1e7 s"):
        pinmask.search(grid=8, holes=5, time="1e9s")


def test_sigxfsz_ignored_and_a_cut_write_is_an_error(tmp_path):
    """CPython ignores SIGXFSZ, so a write past `ulimit -f` fails instead of killing the
    interpreter; the module reports it (RuntimeError naming the file) and leaves no file."""
    script = (
        "import resource, signal, sys, pinmask\n"
        "assert signal.getsignal(signal.SIGXFSZ) == signal.SIG_IGN\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))\n"
        "import numpy as np\n"
        "try:\n"
        "    pinmask.write_image(sys.argv[1], np.full((200, 200), 0.5))\n"
        "except RuntimeError as e:\n"
        "    print(e)\n"
        "    sys.exit(3)\n")
    out = tmp_path / "p.tiff"
    r = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True,
                       env=dict(os.environ))
    assert r.returncode == 3, r.stderr
    assert f"could not write '{out}'" in r.stdout and "File too large" in r.stdout
    assert list(tmp_path.iterdir()) == []


def test_json_readers_speak_the_modules_words(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{\"format\": ")
    readers = [
        lambda: pinmask.load_camera(str(bad)),
        lambda: pinmask.load_mask(str(bad)),
        lambda: pinmask.search(grid=8, holes=5, evals=10, resume=str(bad)),
    ]
    for read in readers:
        with pytest.raises(ValueError) as e:
            read()
        assert "bad.json" in str(e.value) or "resume" in str(e.value)
        assert "[json.exception" not in str(e.value) and "syntax error" in str(e.value)


# ---- fifth round: decode and calibrate, the module's side of the manifest's sections


def test_planes_given_twice_are_refused_naming_both(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    h = np.full((7, 7), 1.0 / 49)
    u = 0.5
    with pytest.raises(ValueError) as e:  # one float step apart
        pinmask.depthmap(cap, psf_stack=[(u, h), (1.0, h), (np.nextafter(u, 1.0), h)], window=5)
    assert ("psf_stack = 0.5 m and 0.50000000000000011 m: planes 0 and 2 hold the same distance "
            "twice") in str(e.value)
    # Just beyond the tolerance (3e-6 relative) the planes are distinct.
    r = pinmask.depthmap(cap, psf_stack=[(u, h), (u * (1 + 3e-6), h)], window=5, smooth=0)
    assert len(r["planes"]) == 2
    with pytest.raises(ValueError, match="hold the same distance twice"):
        pinmask.depthmap(cap, mask=mask7, from_m=1.0, to_m=1.0000001, steps=3, window=5)
    for distances in ([1.0, 1.0], [1.0, 1.0000001], [1.0, 2.0, 1.0]):
        with pytest.raises(ValueError, match=r"distances = .*hold the same distance twice"):
            pinmask.depth(mask7, distances=distances, tv=False)


def test_a_one_pixel_psf_is_refused(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    with pytest.raises(ValueError, match="the PSF is 1 x 1 pixel"):
        pinmask.decode(cap, psf=np.ones((1, 1)))


@pytest.mark.parametrize("channels", [2, 4])
def test_channel_counts_the_files_cannot_hold_are_refused(mask7, tmp_path, channels):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=30)["capture"]
    stack = np.stack([cap] * channels, axis=-1)
    calls = [lambda: pinmask.decode(stack, mask=mask7),
             lambda: pinmask.decode(cap, mask=mask7, dark=stack * 0),
             lambda: pinmask.depthmap(stack, mask=mask7, from_m=1.0, to_m=2.0, window=5),
             lambda: pinmask.write_image(str(tmp_path / "x.tiff"), stack)]
    for call in calls:
        with pytest.raises(ValueError, match=f"an array of {channels} channels: must have 1 "
                                             r"\(grey\) or 3 \(RGB\) channels"):
            call()
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("name,pattern", [
    ("capture-dtype-complex.npy", "npy dtype '<c8' is not supported"),
    ("capture-channels-4.npy", r"npy shape \(28, 28, 4\) is not supported"),
    ("capture-rank-1.npy", r"npy shape \(784\) is not supported"),
    ("capture-trailing-bytes.npy", "trailing bytes"),
    ("capture-version-9.npy", "npy format version 9.0"),
    ("capture-tiff-float16.tiff", "TIFF samples are 16-bit float"),
    ("capture-png-palette-no-plte.png", "Missing PLTE before IDAT"),
])
def test_capture_files_of_the_wrong_kind_are_value_errors(bad_inputs, name, pattern):
    with pytest.raises(ValueError, match=pattern):
        pinmask.read_image(str(bad_inputs / name))



def test_steps_beside_distances_is_refused_as_the_command_does(mask7):
    with pytest.raises(ValueError, match="give either it or from_m/to_m/steps"):
        pinmask.depth(mask7, distances=[1.0, 2.0], steps=3, tv=False)
    r = pinmask.depth(mask7, from_m=1.0, to_m=2.0, tv=False, scenes=["letter-R"])
    assert len(r) == 8  # steps None: the command's --steps 8


def test_a_path_with_a_nul_byte_is_refused_in_the_modules_words(tmp_path):
    """A name with a NUL byte would name its prefix; pybind11's own path conversion failed the
    overload ("incompatible function arguments"). Every path argument says why instead."""
    (tmp_path / "a").write_bytes(b"not an image")
    for name in (str(tmp_path / "a\x00b.tiff"), bytes(tmp_path / "a") + b"\x00b.tiff"):
        with pytest.raises(ValueError, match=r"NUL byte.*no file name can"):
            pinmask.read_image(name)
    with pytest.raises(ValueError, match="NUL byte"):
        pinmask.load_camera(str(tmp_path / "cam\x00.json"))


def test_decode_batch_refuses_a_full_resolution_psf_for_binned_raw_captures():
    """A RAW capture is read 2 x 2 binned; decode() of it alone bins a PSF twice its size, but a
    batch shares one PSF, so decode_batch refuses it as `decode --batch` does."""
    raw = str(pathlib.Path(__file__).resolve().parents[2] / "fuzz/corpus/raw/small.dng")
    rows, cols = np.asarray(pinmask.read_image(raw)[0]).shape
    psf = np.zeros((2 * rows, 2 * cols))
    psf[3, 5], psf[7, 9] = 1.0, 2.0
    with pytest.raises(ValueError, match="one PSF serves every capture of a batch"):
        pinmask.decode_batch([raw], psf=psf)


def test_a_negative_fresnel_number_is_refused():
    """N = d^2 |1/f - 1/f' + 1/u| / (4 lambda) is a magnitude: -0.87 picked the Fresnel kernel."""
    with pytest.raises(ValueError, match=r"fresnel_number = -0\.87: must be >= 0"):
        pinmask.choose_kernel_model(-0.87)
    assert pinmask.choose_kernel_model(0.87)[0] == "fresnel"


def test_a_psf_stack_of_different_sizes_is_refused():
    """The command's stack reader refuses planes of different sizes; an array stack met no check."""
    cap = np.random.default_rng(1).random((64, 64))
    h1, h2 = np.zeros((16, 16)), np.zeros((20, 20))
    h1[3, 3] = h2[4, 4] = 1.0
    with pytest.raises(ValueError, match=r"psf_stack = 20x20: plane 1 differs from plane 0's 16x16"):
        pinmask.depthmap(cap, psf_stack=[(0.5, h1), (1.0, h2)], window=5)
