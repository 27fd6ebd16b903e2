"""write_image's PNG: what the command line writes for the same array. A decode's estimate is in
capture units (far above 1): written with scale='max' (decode's default --scale) and bits=8
(its default --bits) it gives the bytes of `pinmask decode -o x.png`; without a scale, values
outside [0, 1] are a ValueError that says how to scale (they were clamped: a decode came out
white). The pixels are read back by a PNG reader written here and checked against numpy."""
import struct
import zlib

import numpy as np
import pytest

import pinmask


def png_pixels(path):
    """A grey 8- or 16-bit PNG's samples, read here with zlib (no pinmask code, no imaging
    library): chunks, IDAT inflated, each row's filter (none, sub, up, average, Paeth) undone."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b"IHDR":
            cols, rows, bits, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert colour == 0 and interlace == 0 and bits in (8, 16)
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    bpp = bits // 8
    stride = cols * bpp
    raw = zlib.decompress(idat)
    out, prev = [], bytearray(stride)
    for r in range(rows):
        f, line = raw[r * (stride + 1)], bytearray(raw[r * (stride + 1) + 1:(r + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 0xFF
            elif f == 2:
                line[i] = (line[i] + b) & 0xFF
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 0xFF
        out.append(bytes(line))
        prev = line
    dtype = ">u2" if bits == 16 else "u1"
    return np.frombuffer(b"".join(out), dtype=dtype).reshape(rows, cols).astype(np.float64)


@pytest.fixture
def decoded(cli, tmp_path, mask7):
    """A CLI capture, its decode by the module (capture units, peak far above 1)."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("simulate", "m.mask.json", "--scene", "letter-R", "--snr", "30", "--seed", "1",
            "-o", "cap.tiff")
    cap, _ = pinmask.read_image(str(tmp_path / "cap.tiff"))
    np.save(tmp_path / "cap.npy", cap * 1000.0)  # counts
    image = pinmask.decode(cap * 1000.0, mask=str(tmp_path / "m.mask.json"), method="wiener",
                           nsr=0.01)["image"]
    assert image.max() > 100  # capture units
    return image


def test_scale_max_writes_the_png_of_decode(cli, tmp_path, decoded):
    cli.run("decode", "cap.npy", "--mask", "m.mask.json", "--method", "wiener", "--nsr", "0.01",
            "-o", "cli.png")
    pinmask.write_image(str(tmp_path / "py.png"), decoded, scale="max", bits=8)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    # The rule itself, by numpy: negatives to 0, divided by the maximum, 8-bit.
    expected = np.round(np.clip(decoded, 0, None) / decoded.max() * 255)
    got = png_pixels(tmp_path / "py.png")
    assert got.shape == decoded.shape
    assert np.abs(got - expected).max() <= 1 and np.mean(got != expected) < 1e-3
    assert got.max() == 255


def test_scale_factor_and_16_bits_match_decode_scale(cli, tmp_path, decoded):
    factor = 0.6 / decoded.max()
    cli.run("decode", "cap.npy", "--mask", "m.mask.json", "--method", "wiener", "--nsr", "0.01",
            "--scale", repr(factor), "--bits", "16", "-o", "cli.png")
    pinmask.write_image(str(tmp_path / "py.png"), decoded, scale=factor)  # bits 16 by default
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    expected = np.round(np.clip(decoded * factor, 0, 1) * 65535)
    got = png_pixels(tmp_path / "py.png")
    assert np.abs(got - expected).max() <= 1
    assert abs(got.max() - 0.6 * 65535) <= 1


def test_values_outside_unit_range_are_refused_with_how_to_scale(tmp_path, decoded):
    for image in [decoded, np.full((8, 8), -0.25), np.full((8, 8), 1.5)]:
        with pytest.raises(ValueError, match=r"image.*\[0, 1\].*scale='max'.*tiff or \.npy"):
            pinmask.write_image(str(tmp_path / "x.png"), image)
    with pytest.raises(ValueError, match="NaN or Inf"):
        pinmask.write_image(str(tmp_path / "x.png"), np.full((8, 8), np.nan))
    assert not list(tmp_path.glob("x.png*"))  # nothing written, no temporary left
    # Values in [0, 1] are written as they are (the PNG holds them, 16-bit by default).
    ramp = np.linspace(0, 1, 64).reshape(8, 8)
    pinmask.write_image(str(tmp_path / "ramp.png"), ramp)
    assert np.array_equal(png_pixels(tmp_path / "ramp.png"), np.round(ramp * 65535))
    # TIFF and npy hold the raw values whatever their range.
    pinmask.write_image(str(tmp_path / "d.npy"), decoded)
    assert np.array_equal(np.load(tmp_path / "d.npy"), decoded.astype(np.float32))


@pytest.mark.parametrize("kw,error,pattern", [
    (dict(scale="min"), ValueError, "scale.*'max' or a factor"),
    (dict(scale=0.0), ValueError, "scale.*factor > 0"),
    (dict(scale=-2), ValueError, "scale.*factor > 0"),
    (dict(scale=float("inf")), ValueError, "scale.*finite"),
    (dict(scale=True), TypeError, "scale must be 'max' or a number, not bool"),
    (dict(scale=[1]), TypeError, "scale must be 'max' or a number, not list"),
    (dict(bits=12), ValueError, "bits.*8 or 16"),
])
def test_bad_scale_and_bits_are_refused(tmp_path, kw, error, pattern):
    with pytest.raises(error, match=pattern):
        pinmask.write_image(str(tmp_path / "x.png"), np.full((4, 4), 0.5), **kw)
    assert not list(tmp_path.iterdir())


def test_scale_applies_to_png_only(tmp_path):
    for name in ["x.tiff", "x.npy"]:
        with pytest.raises(ValueError, match="scale.*applies to .png only"):
            pinmask.write_image(str(tmp_path / name), np.full((4, 4), 3.0), scale="max")
    assert not list(tmp_path.iterdir())
