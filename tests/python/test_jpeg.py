"""JPEG input (core/image/jpeg_io) against an independent reader: PIL decodes the same files with its own
libjpeg calls (the same libjpeg-turbo, the exact integer IDCT and fancy upsampling by default), so
every uint8 sample must be EQUAL, on real photographs (Debian's python3-skimage data set, PIL comes
with it: scripts/install-deps --with-optional) and on files PIL writes here (grey, 4:2:0 and 4:4:4
colour, progressive). Hostile files raise ValueError naming the file and the problem."""
import pathlib

import numpy as np
import pytest

import pinmask

PHOTOS = pathlib.Path("/usr/lib/python3/dist-packages/skimage/data")


def _pil():
    try:
        from PIL import Image
    except ImportError:
        pytest.fail("PIL not found: install python3-skimage (scripts/install-deps --with-optional)")
    return Image


def _photo(name):
    p = PHOTOS / name
    if not p.exists():
        pytest.fail(f"{p} not found: install python3-skimage (scripts/install-deps --with-optional)")
    return p


def _pil_array(path):
    with _pil().open(path) as im:
        return np.asarray(im)


@pytest.mark.parametrize("name", ["rocket.jpg", "hubble_deep_field.jpg", "retina.jpg"])
def test_photographs_equal_pil_exactly(name):
    path = _photo(name)
    image, full_scale = pinmask.read_image(path)
    ref = _pil_array(path)
    assert full_scale == 255.0
    assert image.shape == ref.shape
    assert np.array_equal(image, ref.astype(np.float64))


@pytest.mark.parametrize("mode,options", [
    ("L", {"quality": 90}),
    ("L", {"quality": 75, "progressive": True}),
    ("RGB", {"quality": 85}),                           # PIL's default: 4:2:0
    ("RGB", {"quality": 95, "subsampling": 0}),          # 4:4:4
    ("RGB", {"quality": 80, "subsampling": 1, "progressive": True}),  # 4:2:2
])
def test_pil_written_files_equal_pil_exactly(tmp_path, mode, options):
    Image = _pil()
    with Image.open(_photo("rocket.jpg")) as im:
        src = im.convert(mode).crop((3, 5, 3 + 211, 5 + 157))  # odd sizes: partial MCUs
    path = tmp_path / "photo.jpg"
    src.save(path, **options)
    image, full_scale = pinmask.read_image(path)
    ref = _pil_array(path)
    assert full_scale == 255.0
    assert image.shape == ref.shape == ((157, 211) if mode == "L" else (157, 211, 3))
    assert np.array_equal(image, ref.astype(np.float64))


def test_truncated_and_cmyk_files_raise(tmp_path):
    with pytest.raises(ValueError, match="truncated.jpg.*truncated or corrupt"):
        pinmask.read_image(_photo("truncated.jpg"))
    Image = _pil()
    good = tmp_path / "good.jpg"
    with Image.open(_photo("rocket.jpg")) as im:
        im.save(good, quality=90)
        im.convert("CMYK").save(tmp_path / "cmyk.jpg", quality=90)
    data = good.read_bytes()
    (tmp_path / "cut.jpg").write_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match="cut.jpg.*truncated"):
        pinmask.read_image(tmp_path / "cut.jpg")
    with pytest.raises(ValueError, match="cmyk.jpg.*CMYK"):
        pinmask.read_image(tmp_path / "cmyk.jpg")
