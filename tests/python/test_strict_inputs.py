"""Python as strict as the command line: wrong dtypes and wrong types are TypeErrors in the
module's words (never pybind11's "Unable to cast"), lengths with units read as the command line
reads them, arrays charged to the memory budget from their shape before any copy, the library's
caps met by both faces, and the file-size limit reported without killing the interpreter."""
import os
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
