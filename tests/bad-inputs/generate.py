#!/usr/bin/python3
"""Writes the malformed-input corpus of tests/bad-inputs/ (run from anywhere; deterministic).

Each file is a small valid pinmask file (from fuzz/corpus/, written by pinmask itself) broken in
one way: truncated, wrong magic, huge or negative declared sizes, NaN/Inf values, deep JSON
nesting, a wrong version, pinholes outside the grid, zero-area polygons, 10^9 declared pixels.
manifest.txt says which command reads each file and what the error message must name.
Standard library only (struct, zlib).
"""
import json
import math
import pathlib
import struct
import zlib

HERE = pathlib.Path(__file__).resolve().parent
SEEDS = HERE.parent.parent / "fuzz" / "corpus"
GIGA_SIDE = 31623  # 31623^2 = 1.0000e9 declared pixels


def write(name, data):
    if isinstance(data, str):
        data = data.encode()
    (HERE / name).write_bytes(data)


def seed(path):
    return (SEEDS / path).read_bytes()


# ---------------------------------------------------------------- mask files (*.mask.json)
MASK_TEXT = seed("mask_json/small.mask.json").decode()
MASK = json.loads(MASK_TEXT)


def mask_variant(name, edit):
    m = json.loads(MASK_TEXT)
    edit(m)
    write(name, json.dumps(m, indent=2) + "\n")


def set_path(*keys_and_value):
    *keys, value = keys_and_value

    def edit(m):
        node = m
        for k in keys[:-1]:
            node = node[k]
        node[keys[-1]] = value

    return edit


def mask_text_replace(name, old, new):
    assert old in MASK_TEXT, old
    write(name, MASK_TEXT.replace(old, new, 1))


write("mask-truncated.mask.json", MASK_TEXT[: len(MASK_TEXT) // 2])
write("mask-empty.mask.json", b"")
write("mask-wrong-magic.mask.json", seed("image/dec8.png"))
mask_variant("mask-wrong-format.mask.json", set_path("format", "pinmask-psf"))
mask_variant("mask-wrong-version.mask.json", set_path("version", 2))
mask_variant("mask-pinhole-outside.mask.json", set_path("pattern", "pinholes", [[1, 0], [3, 7]]))
mask_variant("mask-pinhole-negative.mask.json", set_path("pattern", "pinholes", [[-1, 0], [3, 3]]))
mask_variant("mask-negative-grid.mask.json", set_path("pattern", "n", -7))
mask_variant("mask-giga-grid.mask.json", set_path("pattern", "n", 1000000000))
mask_variant("mask-zero-tiles.mask.json", set_path("pattern", "tiles", [0, 0]))
mask_variant("mask-negative-pinhole-size.mask.json", set_path("optics", "pinhole_m", -0.00044))
mask_variant("mask-zero-pinhole-size.mask.json", set_path("optics", "pinhole_m", 0.0))
mask_variant("mask-negative-sensor.mask.json", set_path("optics", "sensor_px", [-720, 480]))
mask_variant("mask-zero-pixels-per-cell.mask.json", set_path("psf", "pixels_per_cell", 0))
# 65536 pixels per cell (the largest accepted): a 458752^2 PSF, beyond any memory bound.
mask_variant("mask-huge-pixels-per-cell.mask.json", set_path("psf", "pixels_per_cell", 65536))
# A valid 4096 x 4096 grid (the largest): its 32768^2 PSF is refused under a small memory bound.
mask_variant("mask-grid-4096.mask.json", lambda m: (
    set_path("pattern", "n", 4096)(m),
    set_path("pattern", "pinholes", [[0, 0], [100, 2000], [3000, 50]])(m),
    m["provenance"].__setitem__("geometry_hash", "")))
mask_variant("mask-spacing-violation.mask.json",
             set_path("pattern", "pinholes", [[1, 0], [1, 1], [5, 4]]))
mask_variant("mask-duplicate-pinhole.mask.json",
             set_path("pattern", "pinholes", [[1, 0], [1, 0], [5, 4]]))
mask_variant("mask-unknown-key.mask.json", set_path("optics", "focal_mm", 120))
mask_text_replace("mask-nan.mask.json", '"pinhole_m": 0.00044', '"pinhole_m": NaN')
mask_text_replace("mask-inf.mask.json", '"pinhole_m": 0.00044', '"pinhole_m": 1e999')
mask_text_replace("mask-int-overflow.mask.json", '"n": 7', '"n": 99999999999999999999')
mask_text_replace("mask-duplicate-key.mask.json", '"version": 1,', '"version": 1,\n  "version": 1,')
write("mask-deep-nesting.mask.json", "[" * 20000 + "]" * 20000 + "\n")

# ---------------------------------------------------------------- search configurations
CONFIG_TEXT = seed("search_config/written.json").decode()


def config_variant(name, edit):
    c = json.loads(CONFIG_TEXT)
    edit(c)
    write(name, json.dumps(c, indent=2) + "\n")


write("config-truncated.json", CONFIG_TEXT[: len(CONFIG_TEXT) // 2])
write("config-is-a-mask.json", MASK_TEXT)
config_variant("config-wrong-version.json", set_path("version", 7))
config_variant("config-unknown-key.json", set_path("gird", 16))
config_variant("config-negative-seed.json", set_path("seed", -1))
config_variant("config-giga-grid.json", set_path("grid", 1000000000))
config_variant("config-nan-pinhole.json", set_path("optics", "pinhole_m", "NaN"))
config_variant("config-zero-time.json", lambda c: (set_path("time", "0s")(c),
                                                  set_path("evaluations_per_chain", 0)(c)))
write("config-deep-nesting.json", "{\"format\": " + "[" * 20000 + "]" * 20000 + "}\n")

# ---------------------------------------------------------------- npy images


def npy(shape, descr="<f4", data=b"", fortran=False):
    header = "{'descr': '%s', 'fortran_order': %s, 'shape': %s, }" % (
        descr, "True" if fortran else "False", repr(tuple(shape)))
    pad = (64 - (10 + len(header) + 1) % 64) % 64
    header += " " * pad + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + data


CAP_NPY = seed("image/cap.npy")
write("capture-truncated.npy", CAP_NPY[: len(CAP_NPY) // 2])
write("capture-wrong-magic.npy", b"\x93NUMPZ" + CAP_NPY[6:])
write("capture-giga.npy", npy((GIGA_SIDE, GIGA_SIDE), data=b"\0" * 64))
write("capture-huge-truncated.npy", npy((16384, 16384), data=b"\0" * 64))
write("capture-negative-shape.npy", npy((-28, 28), data=b"\0" * 64))
write("capture-big-endian.npy", npy((28, 28), descr=">f4", data=b"\0" * (28 * 28 * 4)))
write("capture-fortran.npy", npy((28, 28), fortran=True, data=b"\0" * (28 * 28 * 4)))
nan_plane = [0.5] * (28 * 28)
nan_plane[100] = math.nan
write("capture-nan.npy", npy((28, 28), data=struct.pack("<784f", *nan_plane)))
write("scene-nan.npy", npy((28, 28), data=struct.pack("<784f", *nan_plane)))
write("psf-zero.npy", npy((28, 28), data=b"\0" * (28 * 28 * 4)))
overflow_plane = [0.0] * (28 * 28)
overflow_plane[10] = overflow_plane[400] = 1e308  # finite values whose sum overflows
write("psf-overflow.npy", npy((28, 28), descr="<f8", data=struct.pack("<784d", *overflow_plane)))
huge_plane = [0.5] * (28 * 28)
huge_plane[300] = 1e300  # float64: a finite capture whose estimate leaves float32's range
write("capture-1e300.npy", npy((28, 28), descr="<f8", data=struct.pack("<784d", *huge_plane)))

# ---------------------------------------------------------------- TIFF images


def tiff(width, height, values=None, bits=32, sample_format=3, declared_bytes=None):
    """A little-endian single-strip TIFF; values (float32) may be absent (declared only)."""
    data = struct.pack("<%df" % len(values), *values) if values is not None else b""
    nbytes = declared_bytes if declared_bytes is not None else width * height * bits // 8
    entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, bits), (259, 3, 1, 1),
               (262, 3, 1, 1), (273, 4, 1, 8), (277, 3, 1, 1), (278, 4, 1, height),
               (279, 4, 1, nbytes), (284, 3, 1, 1), (339, 3, 1, sample_format)]
    ifd_offset = 8 + len(data)
    ifd = struct.pack("<H", len(entries))
    for tag, typ, count, value in entries:
        ifd += struct.pack("<HHII", tag, typ, count, value) if typ == 4 else struct.pack(
            "<HHIHH", tag, typ, count, value, 0)
    ifd += struct.pack("<I", 0)
    return b"II*\0" + struct.pack("<I", ifd_offset) + data + ifd


DEC_TIFF = seed("image/dec.tiff")
write("capture-truncated.tiff", DEC_TIFF[: len(DEC_TIFF) // 2])
write("capture-wrong-magic.tiff", b"MM*\x01" + DEC_TIFF[4:])
write("capture-giga.tiff", tiff(GIGA_SIDE, GIGA_SIDE))
write("capture-zero-width.tiff", tiff(0, 28, values=[]))
inf_plane = [0.5] * (28 * 28)
inf_plane[5] = math.inf
write("capture-inf.tiff", tiff(28, 28, values=inf_plane))
psf_nan = [1.0 / 784] * 784
psf_nan[0] = math.nan
write("psf-nan.tiff", tiff(28, 28, values=psf_nan))
psf_ok = [1.0 / 784] * 784
# PSF files whose sidecars (same stem, .json) are broken.
SIDECAR = json.loads(seed("psf_sidecar/psf_box.json"))
for stem, edit in [
    ("psf-sidecar-version", lambda s: s.__setitem__("version", 7)),
    ("psf-sidecar-size", lambda s: s.__setitem__("size_px", [29, 28])),
    ("psf-sidecar-negative-pitch", lambda s: s.__setitem__("pixel_pitch_m", -3e-05)),
]:
    s = json.loads(json.dumps(SIDECAR))
    edit(s)
    s["files"] = {"tiff": stem + ".tiff"}
    write(stem + ".tiff", tiff(28, 28, values=psf_ok))
    write(stem + ".json", json.dumps(s, indent=2) + "\n")
write("psf-sidecar-deep.tiff", tiff(28, 28, values=psf_ok))
write("psf-sidecar-deep.json", "{\"a\": " * 10000 + "1" + "}" * 10000 + "\n")

# ---------------------------------------------------------------- PNG images


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(
        ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(width, height, idat=b"", bit_depth=8, colour=0):
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", idat) +
            png_chunk(b"IEND", b""))


CAP_PNG = seed("image/cap16.png")
write("capture-truncated.png", CAP_PNG[: len(CAP_PNG) // 2])
write("capture-giga.png", png(GIGA_SIDE, GIGA_SIDE, zlib.compress(b"\0" * 64)))
write("scene-giga.png", png(GIGA_SIDE, GIGA_SIDE, zlib.compress(b"\0" * 64)))
bad_crc = bytearray(CAP_PNG)
bad_crc[29] ^= 0xFF  # inside IHDR's CRC (8 signature + 8 chunk header + 13 data = byte 29)
write("capture-bad-crc.png", bytes(bad_crc))
write("capture-zero-width.png", png(0, 28, zlib.compress(b"\0" * 64)))


def jpeg_segment(marker, payload):
    return b"\xff" + bytes([marker]) + struct.pack(">H", len(payload) + 2) + payload


def jpeg_header(width, height):
    """A baseline grey JPEG up to and including its scan header (no scan data, no EOI): one
    quantisation table, SOF0 with the declared size, two one-code Huffman tables, SOS."""
    one_code = bytes([1] + [0] * 15) + b"\x00"  # a single code of length 1, for symbol 0
    return (b"\xff\xd8" + jpeg_segment(0xDB, b"\x00" + bytes([1]) * 64) +
            jpeg_segment(0xC0, struct.pack(">BHHB", 8, height, width, 1) + b"\x01\x11\x00") +
            jpeg_segment(0xC4, b"\x00" + one_code) + jpeg_segment(0xC4, b"\x10" + one_code) +
            jpeg_segment(0xDA, b"\x01\x01\x00\x00\x3f\x00"))


CAP_JPG = seed("image/dec8.jpg")
write("capture-truncated.jpg", CAP_JPG[: len(CAP_JPG) // 2])
write("capture-giga.jpg", jpeg_header(GIGA_SIDE, GIGA_SIDE))
write("capture-zero-height.jpg", jpeg_header(24, 0))

# ---------------------------------------------------------------- GDSII


def gds_records(data):
    i, out = 0, []
    while i < len(data):
        n, kind, dtype = struct.unpack(">HBB", data[i:i + 4])
        if n == 0:
            break
        out.append((kind, dtype, data[i + 4:i + n]))
        i += n
    return out


def gds_bytes(records):
    return b"".join(struct.pack(">HBB", 4 + len(d), k, t) + d for k, t, d in records)


GDS = seed("gds/clear.gds")
write("layout-truncated.gds", GDS[: len(GDS) // 2])
write("layout-wrong-magic.gds", b"\x00\x06\x7f\x02\x02\x58" + GDS[6:])
write("layout-wrong-version.gds", b"\x00\x06\x00\x02\x7f\xff" + GDS[6:])  # HEADER 32767
recs = gds_records(GDS)
first_xy = next(i for i, r in enumerate(recs) if r[0] == 0x10)
zero_area = list(recs)
zero_area[first_xy] = (0x10, 3, struct.pack(">10i", 0, 0, 1000, 0, 2000, 0, 3000, 0, 0, 0))
write("layout-zero-area.gds", gds_bytes(zero_area))
huge_record = bytearray(GDS)
struct.pack_into(">H", huge_record, 138, 0xFFF0)  # the first XY record claims 65520 bytes
write("layout-huge-record.gds", bytes(huge_record))

# ---------------------------------------------------------------- DXF / Gerber / SVG (text)
DXF = seed("dxf/clear.dxf").decode()
write("layout-truncated.dxf", DXF[: len(DXF) // 2])
dxf_vertex = " 10\n-1540\n 20\n660\n"
assert dxf_vertex in DXF
write("layout-nan.dxf", DXF.replace(dxf_vertex, " 10\nnan\n 20\n660\n", 1))
write("layout-huge-coordinate.dxf", DXF.replace(dxf_vertex, " 10\n1e300\n 20\n660\n", 1))
# The first polyline's four vertices all on y = 660: a zero-area ring.
zero = DXF.replace(" 20\n1100\n", " 20\n660\n", 2)
write("layout-zero-area.dxf", zero)

GBR = seed("gerber/clear.gbr").decode()
write("layout-truncated.gbr", GBR[: len(GBR) // 2])
write("layout-huge-coordinate.gbr",
      GBR.replace("X-1540000Y660000D02*", "X-154000000000000000000000Y660000D02*", 1))
write("layout-zero-area.gbr",
      GBR.replace("X-1100000Y1100000D01*\nX-1540000Y1100000D01*",
                  "X-1100000Y660000D01*\nX-1540000Y660000D01*", 1))

SVG = seed("svg/clear.svg").decode()
write("layout-truncated.svg", SVG[: len(SVG) // 2])
first_path = 'd="M-1540,-660L-1100,-660L-1100,-1100L-1540,-1100Z"'
assert first_path in SVG
write("layout-nan.svg", SVG.replace(first_path, 'd="M-1540,-660LNaN,-660L-1100,-1100L-1540,-1100Z"'))
write("layout-zero-area.svg",
      SVG.replace(first_path, 'd="M-1540,-660L-1100,-660L-1320,-660L-1540,-660Z"'))
write("layout-huge-coordinate.svg",
      SVG.replace(first_path, 'd="M-1540,-660L1e300,-660L-1100,-1100L-1540,-1100Z"'))

# ---------------------------------------------------------------- resource bounds
# Memory: valid all-zero PNGs whose pixels decompress to far more than their bytes.


def zero_png(side):
    comp = zlib.compressobj(9)
    row = b"\0" * (side + 1)  # filter byte 0 + side grey samples
    idat = b"".join(comp.compress(row) for _ in range(side)) + comp.flush()
    return png(side, side, idat)


write("capture-zeros-16000.png", zero_png(16000))  # 249 KB -> 256 M samples (2 GB as double)
write("capture-zeros-4000.png", zero_png(4000))  # 16 KB -> 16 M samples (128 MB as double)

# Nonsense values: PSF sidecars that parse but contradict their image or themselves.


def kernel_edit(key, value):
    return lambda s: s["kernel"].__setitem__(key, value)


for stem, edit in [
    ("psf-sidecar-period", lambda s: s.__setitem__("pixels_per_cell", 5)),  # 7 x 5 != 28
    ("psf-sidecar-grid", lambda s: s.__setitem__("grid_n", 14)),  # 14 x 4 != 28
    ("psf-sidecar-model", kernel_edit("model", "banana")),
    ("psf-sidecar-auto", kernel_edit("model", "auto")),
    ("psf-sidecar-weights", kernel_edit("wavelengths", [[5.5e-07, 1.0], [6.5e-07, 1.0]])),
    ("psf-sidecar-no-wavelength", kernel_edit("wavelengths", [])),
    ("psf-sidecar-zero-wavelength", kernel_edit("wavelengths", [[0.0, 1.0]])),
    ("psf-sidecar-energy", kernel_edit("enclosed_energy", 1.5)),
    ("psf-sidecar-support", kernel_edit("support_px", [40, 10])),
    ("psf-sidecar-zero-support", kernel_edit("support_px", [0, 10])),
    ("psf-sidecar-huge-pitch", lambda s: s.__setitem__("pixel_pitch_m", 1e309)),
    ("psf-sidecar-normalisation", lambda s: s.__setitem__("normalisation", "max=1")),
]:
    s = json.loads(json.dumps(SIDECAR))
    edit(s)
    s["files"] = {"tiff": stem + ".tiff"}
    write(stem + ".tiff", tiff(28, 28, values=psf_ok))
    text = json.dumps(s, indent=2) + "\n"
    write(stem + ".json", text.replace("Infinity", "1e309"))

# Physical quantities: masks with values beyond what later commands accept.
mask_variant("mask-giga-tiles.mask.json", set_path("pattern", "tiles", [1000000000, 1000000000]))
mask_variant("mask-tiles-1025.mask.json", set_path("pattern", "tiles", [1025, 1]))
mask_variant("mask-huge-wavelength.mask.json", set_path("optics", "wavelength_m", 1e300))
mask_variant("mask-tiny-pitch.mask.json", set_path("optics", "pixel_pitch_m", 1e-300))
mask_variant("mask-huge-pinhole.mask.json", set_path("optics", "pinhole_m", 1e300))
mask_variant("mask-huge-sensor-distance.mask.json", set_path("optics", "sensor_distance_m", 1e10))
mask_variant("mask-negative-bandwidth.mask.json", set_path("optics", "bandwidth_m", -3e-8))
mask_variant("mask-bandwidth-beyond-wavelength.mask.json", set_path("optics", "bandwidth_m", 1e-6))


def band_and_list(m):
    m["optics"]["bandwidth_m"] = 3e-8
    m["psf"]["kernel"]["wavelengths"] = [[5.4e-7, 1.0], [5.6e-7, 1.0]]


mask_variant("mask-bandwidth-and-wavelengths.mask.json", band_and_list)
# ---- readers that must implement or refuse: SVG constructs that change
# geometry, DXF units, OASIS records pinmask does not read.
SVG_HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" width="1mm" height="1mm" '
            'viewBox="0 0 1000 1000">\n')
SVG_PATH = '<path d="M0,0L100,0L100,100Z"/>\n'
write("layout-svg-transform.svg", SVG_HEAD + '<g transform="scale(2)">' + SVG_PATH + "</g>\n</svg>\n")
write("layout-svg-viewbox-scale.svg",
      SVG_HEAD.replace("0 0 1000 1000", "0 0 100 100") + SVG_PATH + "</svg>\n")
write("layout-svg-use.svg", SVG_HEAD + SVG_PATH + '<use href="#a" x="5"/>\n</svg>\n')
write("layout-svg-rect.svg", SVG_HEAD + '<rect x="0" y="0" width="10" height="10"/>\n</svg>\n')
write("layout-svg-circle.svg", SVG_HEAD + '<circle cx="5" cy="5" r="3"/>\n</svg>\n')
write("layout-svg-fill-none.svg", SVG_HEAD + SVG_PATH.replace("<path ", '<path fill="none" ') + "</svg>\n")
write("layout-svg-style.svg", SVG_HEAD + SVG_PATH.replace("<path ", '<path style="fill:none" ') + "</svg>\n")
# styling a renderer honours (tests/python/test_check_svg_render.py shows each changes
# rsvg-convert's drawing): refused by name
SVG_STYLED = {
    "display": '<path display="none" ',
    "visibility": '<path visibility="hidden" ',
    "opacity": '<path opacity="0" ',
    "fill-opacity": '<path fill-opacity="0" ',
    "white": '<path fill="#ffffff" ',
    "red": '<path fill="red" ',
    "stroke": '<path stroke="#000000" stroke-width="300" ',
    "clip-path": '<path clip-path="url(#c)" ',
    "class": '<path class="hole" ',
    "single-quote": "<path fill='none' ",
}
for name, start in SVG_STYLED.items():
    write("layout-svg-%s.svg" % name, SVG_HEAD + SVG_PATH.replace("<path ", start) + "</svg>\n")
write("layout-svg-doctype.svg", '<!DOCTYPE svg [<!ATTLIST path fill CDATA "none">]>\n' + SVG_HEAD
      + SVG_PATH + "</svg>\n")
write("layout-svg-stylesheet.svg", '<?xml-stylesheet type="text/css" href="s.css"?>\n' + SVG_HEAD
      + SVG_PATH + "</svg>\n")
# more of the same: each construct changes the drawing (or may), none is what the writer writes
SVG_MORE_ATTRIBUTES = {
    "stroke-width": '<path stroke-width="300" ',
    "fill-rule": '<path fill-rule="evenodd" ',
    "mask": '<path mask="url(#m)" ',
    "filter": '<path filter="url(#blur)" ',
    "path-transform": '<path transform="translate(5,0)" ',
    "marker": '<path marker-start="url(#dot)" ',
    "paint-order": '<path paint-order="stroke" ',
    "current-colour": '<path fill="currentColor" ',
    "gradient": '<path fill="url(#g)" ',
    "grey": '<path fill="#808080" ',
    "xml-space": '<path xml:space="preserve" ',
}
for name, start in SVG_MORE_ATTRIBUTES.items():
    write("layout-svg-%s.svg" % name, SVG_HEAD + SVG_PATH.replace("<path ", start) + "</svg>\n")
SVG_MORE_ELEMENTS = {
    # a stylesheet inside the document restyles every path
    "style-element": "<style>path { fill: none }</style>\n" + SVG_PATH,
    "group-display": '<g display="none">' + SVG_PATH + "</g>\n",
    "group-opacity": '<g opacity="0">' + SVG_PATH + "</g>\n",
    "group-red": '<g fill="red">' + SVG_PATH + "</g>\n",
    "image": '<image href="holes.png" width="100" height="100"/>\n',
    "text": "<text>o</text>\n",
    "polyline": '<polyline points="0,0 100,0 100,100"/>\n',
    "ellipse": '<ellipse cx="5" cy="5" rx="3" ry="2"/>\n',
    "pattern-fill": '<pattern id="p" width="10" height="10">' + SVG_PATH + "</pattern>\n",
    "symbol": '<symbol id="s">' + SVG_PATH + "</symbol>\n",
    "switch": "<switch>" + SVG_PATH + "</switch>\n",
    "anchor": '<a href="#x">' + SVG_PATH + "</a>\n",
    "foreign-object": "<foreignObject><div/></foreignObject>\n",
    "namespaced-path": SVG_PATH.replace("<path ", "<svg:path "),
    "upper-case": SVG_PATH.replace("<path ", "<PATH "),
    "defs": "<defs>" + SVG_PATH + "</defs>\n",
    "cdata": "<![CDATA[ ]]>\n" + SVG_PATH,
    "stylesheet-inside": '<?xml-stylesheet href="s.css"?>\n' + SVG_PATH,
    # a renderer draws nothing inside <desc> or <title>: a pinhole there is not on the plate
    "path-in-desc": "<desc>" + SVG_PATH + "</desc>\n" + SVG_PATH,
    "path-in-title": "<title>" + SVG_PATH + "</title>\n",
}
for name, body in SVG_MORE_ELEMENTS.items():
    write("layout-svg-%s.svg" % name, SVG_HEAD + body + "</svg>\n")
write("layout-svg-root-aspect.svg", SVG_HEAD.replace("<svg ", '<svg preserveAspectRatio="none" ')
      + SVG_PATH + "</svg>\n")
write("layout-svg-root-transform.svg", SVG_HEAD.replace("<svg ", '<svg transform="scale(2)" ')
      + SVG_PATH + "</svg>\n")
write("layout-svg-nested.svg", SVG_HEAD + '<svg viewBox="0 0 500 500" width="1000" height="1000">'
      + SVG_PATH + "</svg>\n</svg>\n")


def dxf_with_insunits(code):
    return DXF.replace("$ACADVER", "$INSUNITS\n 70\n%d\n  9\n$ACADVER" % code, 1)
write("layout-dxf-insunits-feet.dxf", dxf_with_insunits(2))
write("layout-dxf-insunits-unknown.dxf", dxf_with_insunits(99))
# $INSUNITS 1 (inches) contradicts the pinmask comment's units=um
write("layout-dxf-inches-vs-comment.dxf", dxf_with_insunits(1))
# what a viewer draws differently (tests/python/test_check_dxf_styles.py edits an export with
# ezdxf the same ways)
LAYER_ENTRY = "  2\nPINMASK\n 70\n0\n 62\n7\n"
assert LAYER_ENTRY in DXF
write("layout-dxf-layer-off.dxf", DXF.replace(LAYER_ENTRY, "  2\nPINMASK\n 70\n0\n 62\n-7\n", 1))
write("layout-dxf-layer-frozen.dxf", DXF.replace(LAYER_ENTRY, "  2\nPINMASK\n 70\n1\n 62\n7\n", 1))
POLY_HEAD = "POLYLINE\n  8\nPINMASK\n 66\n1\n"
assert POLY_HEAD in DXF
write("layout-dxf-width.dxf", DXF.replace(POLY_HEAD, POLY_HEAD + " 40\n300.0\n 41\n300.0\n", 1))
write("layout-dxf-mirrored.dxf", DXF.replace(POLY_HEAD, POLY_HEAD + "210\n0.0\n220\n0.0\n230\n-1.0\n", 1))
write("layout-dxf-tilted.dxf", DXF.replace(POLY_HEAD, POLY_HEAD + "210\n0.5\n", 1))
write("layout-dxf-invisible.dxf", DXF.replace(POLY_HEAD, POLY_HEAD + " 60\n1\n", 1))
write("layout-dxf-colour-off.dxf", DXF.replace(POLY_HEAD, POLY_HEAD + " 62\n-1\n", 1))
# the same constructs on a VERTEX, and what else changes the drawing or is not read
VERTEX_HEAD = "VERTEX\n  8\nPINMASK\n"
assert VERTEX_HEAD in DXF
DXF_MORE = {
    "lineweight": DXF.replace(POLY_HEAD, POLY_HEAD + "370\n50\n", 1),
    "vertex-width": DXF.replace(VERTEX_HEAD, VERTEX_HEAD + " 40\n300.0\n", 1),
    "vertex-invisible": DXF.replace(VERTEX_HEAD, VERTEX_HEAD + " 60\n1\n", 1),
    "vertex-colour-off": DXF.replace(VERTEX_HEAD, VERTEX_HEAD + " 62\n-3\n", 1),
    "vertex-mirrored": DXF.replace(VERTEX_HEAD, VERTEX_HEAD + "230\n-1.0\n", 1),
    "vertex-bulge": DXF.replace(VERTEX_HEAD, VERTEX_HEAD + " 42\n1.0\n", 1),
    "polyline-3d": DXF.replace(POLY_HEAD + " 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n1\n",
                               POLY_HEAD + " 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n9\n", 1),
    "polyline-open": DXF.replace(POLY_HEAD + " 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n1\n",
                                 POLY_HEAD + " 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n0\n", 1),
    "layer-off-and-frozen": DXF.replace(LAYER_ENTRY, "  2\nPINMASK\n 70\n1\n 62\n-7\n", 1),
    "tilted-y": DXF.replace(POLY_HEAD, POLY_HEAD + "220\n0.25\n", 1),
    "insert": DXF.replace("  0\nPOLYLINE\n", "  0\nINSERT\n  8\nPINMASK\n  2\nHOLE\n"
                          " 10\n0.0\n 20\n0.0\n  0\nPOLYLINE\n", 1),
    "hatch": DXF.replace("  0\nPOLYLINE\n", "  0\nHATCH\n  8\nPINMASK\n  0\nPOLYLINE\n", 1),
    "solid": DXF.replace("  0\nPOLYLINE\n", "  0\nSOLID\n  8\nPINMASK\n  0\nPOLYLINE\n", 1),
    "no-seqend": DXF.replace("  0\nSEQEND\n", "  0\nPOLYLINE\n", 1),
    "vertex-without-y": DXF.replace(" 10\n-1540\n 20\n660\n", " 10\n-1540\n", 1),
}
for name, text in DXF_MORE.items():
    assert text != DXF, name
    write("layout-dxf-%s.dxf" % name, text)
write("layout-dxf-insunits-cm.dxf", dxf_with_insunits(5))
# a Gerber that draws nothing: its header and M02 only
write("layout-empty.gbr", GBR[: GBR.index("G36*")] + "M02*\n")

OAS = seed("oasis/clear.oas")
write("layout-truncated.oas", OAS[: len(OAS) // 2])
write("layout-wrong-magic.oas", b"%SEMI-OASIX\r\n" + OAS[13:])
# record 17 (PLACEMENT) in place of the first RECTANGLE (id 20) after the CELL/XYRELATIVE records
first_rect = OAS.index(b"\x10\x14") + 1
write("layout-placement.oas", OAS[:first_rect] + b"\x11" + OAS[first_rect + 1:])
write("layout-cblock.oas", OAS[:first_rect] + b"\x22" + OAS[first_rect + 1:])
write("layout-circle.oas", OAS[:first_rect] + b"\x1b" + OAS[first_rect + 1:])
# a grid repetition of 2^24 + 1 by 2^24 + 1 elements
start = b"%SEMI-OASIS\r\n\x01\x031.0\x00\xe8\x07\x00" + bytes(12)
cell = b"\x0e\x04CELL"
rect = b"\x14\xdf\x01\x00\x0a\x00\x00\x01\xff\xff\xff\x07\xff\xff\xff\x07\x02\x02"
end = b"\x02\xfc\x01" + bytes(252) + b"\x00"
write("layout-giga-repetition.oas", start + cell + rect + end)
# one 45 x 45 grid repetition (2,025 squares) placed again by 10^4 RECTANGLE records that reuse
# it (repetition type 0): 20 million squares from a 30 KB file
grid_rect = b"\x14\xdf\x01\x00\x0a\x00\x00\x01\x2b\x2b\x14\x14"
write("layout-reused-repetition.oas", start + cell + grid_rect + b"\x14\x04\x00" * 10000 + end)


def oas_uint(v):
    """OASIS unsigned integer: little-endian base-128, high bit = more bytes follow."""
    out = bytearray()
    while True:
        b = v & 0x7F
        v >>= 7
        out.append(b | (0x80 if v else 0))
        if not v:
            return bytes(out)


# a 10-unit square (RECTANGLE, info S W X Y R D L) at the origin on layer 1 / datatype 0,
# then the repetition bytes
RECT_HEAD = b"\x14\xdf\x01\x00\x0a\x00\x00"


def oas_rect(repetition):
    return start + cell + RECT_HEAD + repetition + end


# Repetitions: every type's counts and extents bounded before anything is expanded.
OAS_REPETITIONS = {
    # type 0 reuses the previous repetition: there is none
    "type0-first": b"\x00",
    "type12": b"\x0c",
    # a row (type 2) and a column (type 3) of 2^25 + 2 elements: beyond the 2^24 per dimension
    "row-2e25": b"\x02" + oas_uint(1 << 25) + oas_uint(20),
    "column-2e25": b"\x03" + oas_uint(1 << 25) + oas_uint(20),
    # 1,002 elements 2^39 units apart: the extent leaves 2^40 database units
    "row-beyond-2e40": b"\x02" + oas_uint(1000) + oas_uint(1 << 39),
    # a 2^24 x 2^24 grid given by two g-deltas (type 8): 2.8e14 elements
    "gdelta-grid-giga": b"\x08" + oas_uint((1 << 24) - 2) * 2 + oas_uint(1 << 4)
                        + oas_uint((1 << 4) | (1 << 1)),
    # 2^24 elements along a diagonal g-delta (type 9): 1.3 GB of offsets before any shape
    "diagonal-2e24": b"\x09" + oas_uint((1 << 24) - 2) + oas_uint((1 << 4) | (4 << 1)),
    # arbitrary x offsets (type 4) that add up past 2^40
    "steps-beyond-2e40": b"\x04" + oas_uint(1) + oas_uint((1 << 40) - 1) * 2,
    # arbitrary g-deltas on a 2^30 grid (type 11): one step of 2^11 grid units is 2^41 units
    "gdelta-steps-beyond-2e40": b"\x0b" + oas_uint(0) + oas_uint(1 << 30)
                                + oas_uint(((1 << 11) << 4)),
    # a count whose varint runs past 64 bits
    "count-65-bits": b"\x02" + b"\xff" * 9 + b"\x7f" + oas_uint(20),
    # the file ends inside the repetition
    "truncated": b"\x01" + oas_uint(43),
}
for name, rep in OAS_REPETITIONS.items():
    write("layout-repetition-%s.oas" % name, oas_rect(rep) if name != "truncated"
          else start + cell + RECT_HEAD + rep)
# one repetition of each other shape reused by 10^4 records (type 0): 20 million squares again
row_rect = RECT_HEAD + b"\x02" + oas_uint(2023) + oas_uint(20)
write("layout-reused-row.oas", start + cell + row_rect + b"\x14\x04\x00" * 10000 + end)
diag_rect = RECT_HEAD + b"\x09" + oas_uint(2023) + oas_uint((20 << 4) | (4 << 1))
write("layout-reused-diagonal.oas", start + cell + diag_rect + b"\x14\x04\x00" * 10000 + end)

# ---------------------------------------------------------------- search checkpoints
# A checkpoint of `pinmask search --grid 16 --holes 20 --evals 3000 --threads 1 --seed 1
# --strategy random --checkpoint-every 1000` at its second boundary (the manifest's resume
# lines give those flags), broken one way per file. The config is what that command writes; the
# one candidate is a real pattern of that search with its objective, so only the edit is wrong.
CHECKPOINT_CONFIG = json.loads(
    '{"format": "pinmask-search-config", "version": 1, "strategy": "random", '
    '"evaluations_per_chain": 3000, "ranks": 1, "threads": 1, "seed": 1, "top": 5, "grid": 16, '
    '"holes": 20, "max_holes": 0, "tiles": 2, "min_spacing_cells": 2.0, "keep_out": "none", '
    '"pixels_per_cell": 8, "kernel_requested": "auto", "kernel_path": "", '
    '"noise": {"model": "gaussian", "snr_db": 30.0}, "filter": "auto", '
    '"prior": {"family": "natural", "scenes": 16}, "weights": {"analytic_wiener": 1.0, '
    '"max_sidelobe": 0.0, "sidelobe_energy": 0.0, "min_spectrum": 0.0}, '
    '"rerank_scenes": ["letter-R", "usaf", "siemens-star"], "rerank_tv": true, '
    '"allow_spectral_zeros": false, "rank_by": "wiener", "objective": "nominal", "robust": "", '
    '"optics": {"object_distance_m": 6.0, "lens_focal_m": 0.12, "sensor_distance_m": 0.055, '
    '"wavelength_m": 5.5e-07, "pixel_pitch_m": 3e-05, "pinhole_m": 0.00044, '
    '"sensor_px": [720, 480]}, "migrate_every": 0, "checkpoint_every": 1000}')
CHECKPOINT_HOLES = [[1, 0], [1, 11], [3, 3], [3, 9], [5, 2], [6, 11], [7, 1], [8, 4], [8, 7],
                    [8, 10], [9, 2], [9, 12], [10, 9], [11, 0], [12, 3], [12, 11], [13, 5],
                    [14, 1], [15, 9], [15, 15]]
CHECKPOINT_BEST = -21.835705618815933  # that pattern's objective (negative analytic PSNR, dB)


def checkpoint_pattern(holes=None, n=16):
    return {"n": n, "tiles_rows": 2, "tiles_cols": 2, "min_spacing_cells": 2.0,
            "pinholes": holes if holes is not None else [list(h) for h in CHECKPOINT_HOLES]}


def checkpoint_log(evaluations):
    """The log a chain keeps: 1, 2, .., 16 evaluations, then ~19 % steps (optimize/search/search)."""
    log, e = [], 1
    while e <= evaluations:
        log.append([e, CHECKPOINT_BEST])
        e = max(e + 1, math.ceil(e * 1.19))
    return log, e


def fnv1a64(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def sealed(c):
    """The file's text with its checksum: FNV-1a 64 of the text with the value as 16 zeros."""
    c["checksum"] = "0" * 16
    text = json.dumps(c) + "\n"
    key = '"checksum": "' + "0" * 16
    at = text.rindex(key) + len(key) - 16
    return text[:at] + fnv1a64(text.encode()) + text[at + 16:]


def checkpoint(edit, seal=True):
    """A checkpoint broken by `edit`: sealed after the edit (a forger's file: its fields must be
    checked one by one), or, with seal=False, edited after sealing (refused by the checksum)."""
    log, next_at = checkpoint_log(2000)
    chain = {"rng": " ".join(str(i) for i in range(1, 313)) + " 312",
             "evaluations": 2000, "best_objective": CHECKPOINT_BEST, "next_log_at": next_at,
             "log": log, "top_capacity": 5,
             "top": [{"objective": CHECKPOINT_BEST, "pattern": checkpoint_pattern()}],
             "start": None, "best_per_holes": []}
    c = {"format": "pinmask-search-checkpoint", "version": 2,
         "config": json.loads(json.dumps(CHECKPOINT_CONFIG)), "segment": 2,
         "evaluations_between_boundaries": 1000, "chains": [chain]}
    if not seal:
        text = sealed(c)
        c = json.loads(text)
        edit(c, c["chains"][0])
        return json.dumps(c) + "\n"
    edit(c, chain)
    return sealed(c)


def shifted_holes(dc):
    return sorted([r, (c + dc) % 16] for r, c in CHECKPOINT_HOLES)


def set_keys(**kv):
    return lambda c, ch: ch.update(kv)


CHECKPOINT_EDITS = {
    # claims beyond the run: counts and objectives no chain of it can have
    "evals-1e9": set_keys(evaluations=10**9),
    "evals-over-budget": set_keys(evaluations=5000),
    "evals-negative": set_keys(evaluations=-1),
    "objective-minus-1000": lambda c, ch: (ch.update(best_objective=-1000.0),
                                           ch["top"][0].update(objective=-1000.0)),
    "best-not-listed": set_keys(best_objective=-22.5),
    "candidates-without-evaluations": lambda c, ch: ch.update(evaluations=0, log=[]),
    # patterns of another search
    "pattern-grid-32": lambda c, ch: ch["top"][0].update(pattern=checkpoint_pattern(n=32)),
    "pattern-19-holes": lambda c, ch: ch["top"][0].update(
        pattern=checkpoint_pattern([list(h) for h in CHECKPOINT_HOLES[:19]])),
    "start-grid-32": set_keys(start=checkpoint_pattern(n=32)),
    "pattern-outside": lambda c, ch: ch["top"][0].update(
        pattern=checkpoint_pattern([[16, 0]] + [list(h) for h in CHECKPOINT_HOLES[1:]])),
    "top-worse-first": lambda c, ch: ch.update(top=[
        {"objective": -21.0, "pattern": checkpoint_pattern(shifted_holes(1))},
        {"objective": CHECKPOINT_BEST, "pattern": checkpoint_pattern()}]),
    "top-repeated": lambda c, ch: ch.update(top=[
        {"objective": CHECKPOINT_BEST, "pattern": checkpoint_pattern()},
        {"objective": CHECKPOINT_BEST, "pattern": checkpoint_pattern()}]),
    "top-capacity-0": set_keys(top_capacity=0),
    "per-holes-zero": set_keys(best_per_holes=[
        {"holes": 0, "objective": CHECKPOINT_BEST, "pattern": checkpoint_pattern()}]),
    # logs: bounded, ordered, within the chain's counts, a best that never rises
    "log-4097": lambda c, ch: ch.update(log=[[e, None] for e in range(1, 4098)],
                                        evaluations=3000),
    "log-unordered": lambda c, ch: ch["log"].insert(5, ch["log"].pop(3)),
    "log-beyond-evaluations": lambda c, ch: ch["log"].append([2500, CHECKPOINT_BEST]),
    "log-best-rises": lambda c, ch: ch["log"][-1].__setitem__(1, -20.0),
    "log-not-pairs": lambda c, ch: ch["log"].append([2000]),
    # the file itself
    "wrong-format": lambda c, ch: c.update(format="pinmask-search-config"),
    "version-1": lambda c, ch: c.update(version=1),
    "version-3": lambda c, ch: c.update(version=3),
    "rng-garbage": set_keys(rng="not a generator state"),
    "segment-0": lambda c, ch: c.update(segment=0),
    "every-0": lambda c, ch: c.update(evaluations_between_boundaries=0),
    "two-chains": lambda c, ch: c["chains"].append(json.loads(json.dumps(ch))),
    "other-config": lambda c, ch: c["config"].update(grid=12),
    "unknown-key": set_keys(evaluations_total=2000),
    # generator states the stream reader would wrap or misread
    "rng-negative": set_keys(rng="-5 " + " ".join(str(i) for i in range(2, 313)) + " 312"),
    "rng-2-64": set_keys(rng="18446744073709551616 " + " ".join(str(i) for i in range(2, 313))
                         + " 312"),
    "rng-index-313": set_keys(rng=" ".join(str(i) for i in range(1, 313)) + " 313"),
    "rng-short": set_keys(rng=" ".join(str(i) for i in range(1, 300))),
    "rng-long": set_keys(rng=" ".join(str(i) for i in range(1, 313)) + " 312 5"),
    "rng-float": set_keys(rng="1.5 " + " ".join(str(i) for i in range(2, 313)) + " 312"),
    "rng-hex": set_keys(rng="0x10 " + " ".join(str(i) for i in range(2, 313)) + " 312"),
    # a segment, a boundary interval and counts this run cannot have written
    "segment-huge": lambda c, ch: c.update(segment=10**15),
    "segment-3": lambda c, ch: c.update(segment=3),
    "segment-negative": lambda c, ch: c.update(segment=-2),
    "every-500": lambda c, ch: c.update(evaluations_between_boundaries=500),
    "evals-below-boundary": lambda c, ch: ch.update(
        evaluations=1500, log=checkpoint_log(1500)[0], next_log_at=checkpoint_log(1500)[1]),
    # the log is the chain's own: its steps and its next step
    "log-entry-missing": lambda c, ch: ch["log"].pop(4),
    "log-entry-shifted": lambda c, ch: ch["log"][20].__setitem__(0, ch["log"][20][0] + 1),
    "log-next-wrong": set_keys(next_log_at=2100),
    "log-truncated": lambda c, ch: ch["log"].pop(),
}
# edited after it was written: each field a user or a fault might change, refused by the checksum
CHECKPOINT_TAMPERED = {
    "evaluations": set_keys(evaluations=1999),
    "rng": set_keys(rng=" ".join(str(i) for i in range(2, 314)) + " 312"),
    "segment": lambda c, ch: c.update(segment=1),
    "log-entry": lambda c, ch: ch["log"][3].__setitem__(1, -22.0),
    "objective": lambda c, ch: ch["top"][0].update(objective=-21.9),
    "best": set_keys(best_objective=-21.9),
    "config": lambda c, ch: c["config"].update(seed=2),
    "next-log-at": set_keys(next_log_at=2001),
    "pinhole": lambda c, ch: ch["top"][0]["pattern"]["pinholes"][0].__setitem__(1, 2),
    "checksum-missing": lambda c, ch: c.pop("checksum"),
    "checksum-short": lambda c, ch: c.update(checksum="abc"),
    "checksum-number": lambda c, ch: c.update(checksum=12),
    "checksum-digit": lambda c, ch: c.update(
        checksum=c["checksum"][:-1] + ("0" if c["checksum"][-1] != "0" else "1")),
}
for name, edit in CHECKPOINT_EDITS.items():
    write("checkpoint-%s.json" % name, checkpoint(edit))
for name, edit in CHECKPOINT_TAMPERED.items():
    write("checkpoint-tampered-%s.json" % name, checkpoint(edit, seal=False))

# A valid camera file: the input that outputs of the same run (a checkpoint, a saved camera) are
# aimed at, and must not replace.
write("camera-valid.camera.json", seed("camera_json/paper.camera.json"))
write("checkpoint-truncated.json", checkpoint(lambda c, ch: None)[:700])

# ---------------------------------------------------------------- camera RAW (raw-*)
# A minimal uncompressed DNG (32 x 24 pixels, 16-bit RGGB CFA, BlackLevel 64, WhiteLevel 4095,
# values 64 + (10 r + c) mod 4000), broken one way per file; its valid form is the seed of
# fuzz/corpus/raw/ (fuzz_raw). Read through LibRaw by extension (core/image/raw_io).
RAW_SEEDS = HERE.parent.parent / "fuzz" / "corpus" / "raw"

SHORT, LONG, ASCII, BYTE, SRATIONAL = 3, 4, 2, 1, 10


def raw_dng(width=32, height=24, bps=16, compression=1, photometric=32803, cfa=(0, 1, 1, 2),
        magic=b"II*\x00", ifd_offset=None, data_fraction=1.0, black=64, white=4095,
        make="pinmask", model="test sensor"):
    pixels = bytearray()
    for r in range(height if width * height < 10_000_000 else 1):
        for c in range(width):
            pixels += struct.pack("<H", min(65535, black + (10 * r + c) % 4000))
    pixels = bytes(pixels[: int(len(pixels) * data_fraction)])
    entries = []  # (tag, type, count, value bytes)

    def add(tag, typ, values):
        if typ == ASCII:
            data = values.encode() + b"\x00"
            entries.append((tag, typ, len(data), data))
            return
        fmt = {SHORT: "<H", LONG: "<I", BYTE: "<B", SRATIONAL: "<ii"}[typ]
        data = b"".join(struct.pack(fmt, *(v if isinstance(v, tuple) else (v,))) for v in values)
        entries.append((tag, typ, len(values), data))

    add(254, LONG, [0])
    add(256, LONG, [width])
    add(257, LONG, [height])
    add(258, SHORT, [bps])
    add(259, SHORT, [compression])
    add(262, SHORT, [photometric])
    add(271, ASCII, make)
    add(272, ASCII, model)
    add(273, LONG, [0])  # patched below
    add(277, SHORT, [1])
    add(278, LONG, [height])
    add(279, LONG, [width * height * bps // 8])
    add(284, SHORT, [1])
    add(33421, SHORT, [2, 2])
    add(33422, BYTE, list(cfa))
    add(50706, BYTE, [1, 4, 0, 0])
    add(50708, ASCII, "pinmask test sensor")
    add(50714, LONG, [black])
    add(50717, LONG, [white])
    add(50721, SRATIONAL, [(1, 1), (0, 1), (0, 1), (0, 1), (1, 1), (0, 1), (0, 1), (0, 1), (1, 1)])
    add(50778, SHORT, [21])
    entries.sort()
    ifd_at = 8
    ifd_size = 2 + 12 * len(entries) + 4
    extra_at = ifd_at + ifd_size
    extra = bytearray()
    offsets = {}
    for tag, typ, count, data in entries:
        if len(data) > 4:
            offsets[tag] = extra_at + len(extra)
            extra += data + (b"\x00" if len(data) % 2 else b"")
    strip_at = extra_at + len(extra)
    ifd = struct.pack("<H", len(entries))
    for tag, typ, count, data in entries:
        if tag == 273:
            data = struct.pack("<I", strip_at)
        if len(data) > 4:
            ifd += struct.pack("<HHII", tag, typ, count, offsets[tag])
        else:
            ifd += struct.pack("<HHI", tag, typ, count) + data.ljust(4, b"\x00")
    ifd += struct.pack("<I", 0)
    head = magic + struct.pack("<I", ifd_at if ifd_offset is None else ifd_offset)
    return head + ifd + bytes(extra) + pixels


RAW_SEEDS.mkdir(parents=True, exist_ok=True)
(RAW_SEEDS / "small.dng").write_bytes(raw_dng())
# Crashes Debian 12's LibRaw 0.20.2 (an abort in its Hasselblad model parsing; core/image/raw_io runs
# LibRaw in a child process, so the file is refused): a seed, so every fuzz run takes that path.
(RAW_SEEDS / "hasselblad-long-model.dng").write_bytes(raw_dng(make="Hasselblad", model="M" * 63))
write("raw-empty.dng", b"")
write("raw-text.nef", "this is a text file named like a Nikon RAW file\n" * 4)
write("raw-wrong-magic.dng", raw_dng(magic=b"XX*\x00"))
write("raw-zero-width.dng", raw_dng(width=0))
write("raw-tiny.dng", raw_dng(width=8, height=8))
write("raw-giga.dng", raw_dng(width=40000, height=40000))
write("raw-ifd-beyond-eof.dng", raw_dng(ifd_offset=10_000_000))
write("raw-bps-32.dng", raw_dng(bps=32))
write("raw-compression-99.dng", raw_dng(compression=99))
write("raw-white-below-black.dng", raw_dng(black=3000, white=100))
write("raw-huge-truncated.dng", raw_dng(width=6000, height=4000, data_fraction=0.0))

# ---------------------------------------------------------------- PSF stacks (depthmap --psf-stack)


def psf_stack(name, planes, fmt="pinmask-psf-stack"):
    write(name, json.dumps({"format": fmt, "version": 1, "planes": [
        {"object_distance_m": u, "psf": f} for u, f in planes]}, indent=2) + "\n")


write("psf-stack-ok.tiff", tiff(28, 28, values=psf_ok))
write("psf-stack-small.tiff", tiff(20, 20, values=[1.0 / 400] * 400))
write("psf-stack-large.tiff", tiff(32, 32, values=[1.0 / 1024] * 1024))
psf_negative = [1.0 / 784] * 784
psf_negative[7] = -0.5
write("psf-stack-negative.tiff", tiff(28, 28, values=psf_negative))
write("psf-stack-dark.tiff", tiff(28, 28, values=[0.0] * 784))
psf_stack("psf-stack-wrong-format.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "psf-stack-ok.tiff")],
          fmt="pinmask-mask")
psf_stack("psf-stack-one-plane.json", [(0.5, "psf-stack-ok.tiff")])
psf_stack("psf-stack-zero-distance.json", [(0.5, "psf-stack-ok.tiff"), (0, "psf-stack-ok.tiff")])
psf_stack("psf-stack-same-distance.json", [(0.5, "psf-stack-ok.tiff"),
                                           (0.5, "psf-stack-ok.tiff")])
psf_stack("psf-stack-missing-psf.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "no-such-psf.tiff")])
psf_stack("psf-stack-nan.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "psf-nan.tiff")])
psf_stack("psf-stack-negative.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "psf-stack-negative.tiff")])
psf_stack("psf-stack-dark.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "psf-stack-dark.tiff")])
psf_stack("psf-stack-sizes-differ.json", [(0.5, "psf-stack-ok.tiff"),
                                          (1.0, "psf-stack-small.tiff")])
psf_stack("psf-stack-larger-than-capture.json", [(0.5, "psf-stack-large.tiff"),
                                                 (1.0, "psf-stack-large.tiff")])
write("psf-stack-string-distance.json", json.dumps({
    "format": "pinmask-psf-stack", "version": 1,
    "planes": [{"object_distance_m": "0.5m", "psf": "psf-stack-ok.tiff"},
               {"object_distance_m": 1.0, "psf": "psf-stack-ok.tiff"}]}) + "\n")

# ---------------------------------------------------------------- film identity (check)
# What identifies the film: GDSII/OASIS layer and datatype, DXF layer names, Gerber polarity.
# Each file is a corpus export edited one way, beside a copy of its export's sidecar (listing
# the file under its new name, the mask given relative to the sidecar) unless the name says
# "no-sidecar": check compares the file with the sidecar's entry, else with --vendor / --tone.
FILM_MASK = "../../fuzz/corpus/mask_json/small.mask.json"


def film_sidecar(seed_name, file_name, edit=None):
    side = json.loads(seed("export_sidecar/" + seed_name))
    side["mask"]["path"] = FILM_MASK
    ext = file_name.rsplit(".", 1)[1]
    for f in side["files"]:
        if f["name"].endswith("." + ext):
            f["name"] = file_name
            if edit:
                edit(f)
    write(file_name.rsplit(".", 1)[0] + ".export.json",
          json.dumps(side, indent=2, sort_keys=True) + "\n")


def film(name, data, seed_name=None, edit=None):
    write(name, data)
    if seed_name:
        film_sidecar(seed_name, name, edit)


def gds_edit(kind, value, first_only=False):
    out, done = [], False
    for k, t, d in gds_records(GDS):
        if k == kind and not (first_only and done):
            d, done = struct.pack(">h", value), True
        out.append((k, t, d))
    return gds_bytes(out) + b"\0" * (len(GDS) - len(gds_bytes(gds_records(GDS))))


GDS_LAYER, GDS_DATATYPE = 0x0D, 0x0E
film("film-gds-one-on-layer2.gds", gds_edit(GDS_LAYER, 2, first_only=True), "clear.export.json")
film("film-gds-all-on-layer5.gds", gds_edit(GDS_LAYER, 5), "clear.export.json")
film("film-gds-datatype3.gds", gds_edit(GDS_DATATYPE, 3), "clear.export.json")
film("film-gds-one-on-layer2-no-sidecar.gds", gds_edit(GDS_LAYER, 2, first_only=True))
film("film-gds-all-on-layer5-no-sidecar.gds", gds_edit(GDS_LAYER, 5))
# the file as exported, its sidecar saying another layer, or none (an older sidecar)
film("film-gds-sidecar-layer7.gds", GDS, "clear.export.json",
     lambda f: f.__setitem__("detail", "layer 7/0"))
film("film-gds-sidecar-datatype1.gds", GDS, "clear.export.json",
     lambda f: f.__setitem__("detail", "layer 1/1"))
film("film-gds-sidecar-no-detail.gds", GDS, "clear.export.json", lambda f: f.pop("detail"))

# OASIS: the first element sets the modal layer and datatype every later element uses
OAS_FIRST = OAS.index(b"\x10\x14") + 1  # RECTANGLE, info byte, layer, datatype
assert OAS[OAS_FIRST + 2:OAS_FIRST + 4] == b"\x01\x00"
film("film-oas-all-on-layer5.oas", OAS[:OAS_FIRST + 2] + b"\x05" + OAS[OAS_FIRST + 3:],
     "oasis.export.json")
film("film-oas-datatype3.oas", OAS[:OAS_FIRST + 3] + b"\x03" + OAS[OAS_FIRST + 4:],
     "oasis.export.json")
film("film-oas-sidecar-layer2.oas", OAS, "oasis.export.json",
     lambda f: f.__setitem__("detail", "layer 2/0"))
film("film-oas-all-on-layer5-no-sidecar.oas", OAS[:OAS_FIRST + 2] + b"\x05" + OAS[OAS_FIRST + 3:])
# two 10-unit squares, the second on layer 2 (its info byte sets L again) or datatype 1
square1 = b"\x14\xdb\x01\x00\x0a\x00\x00"
film("film-oas-two-layers-no-sidecar.oas", start + cell + square1 + b"\x14\xdb\x02\x00\x0a\x28\x00"
     + end)
film("film-oas-two-datatypes-no-sidecar.oas",
     start + cell + square1 + b"\x14\xdb\x01\x01\x0a\x28\x00" + end)

# DXF: every entity's layer (group 8) and the LAYER table entry
DXF_ENTITY_LAYER = "  8\nPINMASK\n"
assert DXF.count(DXF_ENTITY_LAYER) > 3
renamed = DXF.replace(DXF_ENTITY_LAYER, "  8\nMASK\n").replace("  2\nPINMASK\n", "  2\nMASK\n")
film("film-dxf-renamed-layer.dxf", renamed, "clear.export.json")
film("film-dxf-renamed-layer-no-sidecar.dxf", renamed)
film("film-dxf-one-on-layer-0.dxf", DXF.replace("POLYLINE\n" + DXF_ENTITY_LAYER, "POLYLINE\n", 1),
     "clear.export.json")
film("film-dxf-one-on-other-layer.dxf",
     DXF.replace("POLYLINE\n" + DXF_ENTITY_LAYER, "POLYLINE\n  8\nHOLES\n", 1), "clear.export.json")
film("film-dxf-one-on-other-layer-no-sidecar.dxf",
     DXF.replace("POLYLINE\n" + DXF_ENTITY_LAYER, "POLYLINE\n  8\nHOLES\n", 1))
film("film-dxf-lower-case-layer.dxf",
     DXF.replace(DXF_ENTITY_LAYER, "  8\npinmask\n").replace("  2\nPINMASK\n", "  2\npinmask\n"),
     "clear.export.json")
film("film-dxf-sidecar-other-layer.dxf", DXF, "clear.export.json",
     lambda f: f.__setitem__("detail", "layer FILM"))

# Gerber: the file polarity attribute, against the sidecar's tone and the file's own comment
GBR_DARK = seed("gerber/dark.gbr").decode()
NEGATIVE, POSITIVE = "%TF.FilePolarity,Negative*%\n", "%TF.FilePolarity,Positive*%\n"
assert NEGATIVE in GBR and POSITIVE in GBR_DARK
film("film-gbr-positive.gbr", GBR.replace(NEGATIVE, POSITIVE), "clear.export.json")
film("film-gbr-no-polarity.gbr", GBR.replace(NEGATIVE, ""), "clear.export.json")
film("film-gbr-dark-negative.gbr", GBR_DARK.replace(POSITIVE, NEGATIVE), "dark.export.json")
film("film-gbr-dark-no-polarity.gbr", GBR_DARK.replace(POSITIVE, ""), "dark.export.json")
film("film-gbr-positive-no-sidecar.gbr", GBR.replace(NEGATIVE, POSITIVE))
film("film-gbr-clear-no-sidecar.gbr", GBR)
film("film-gbr-sidecar-dark.gbr", GBR, "clear.export.json")
# (its sidecar says dark: the geometry of the clear export cannot be the dark design either)
side = json.loads((HERE / "film-gbr-sidecar-dark.export.json").read_text())
side["geometry"]["tone"] = "dark"
write("film-gbr-sidecar-dark.export.json", json.dumps(side, indent=2, sort_keys=True) + "\n")
# image and level polarity commands (the writer draws dark level only): refused by the reader
LPD = "%LPD*%\n"
assert LPD in GBR
film("film-gbr-level-clear.gbr", GBR.replace(LPD, "%LPC*%\n"), "clear.export.json")
film("film-gbr-level-clear-later.gbr", GBR.replace("G36*", "%LPC*%\nG36*", 1), "clear.export.json")
film("film-gbr-image-negative.gbr", GBR.replace(LPD, "%IPNEG*%\n" + LPD), "clear.export.json")
film("film-gbr-image-positive.gbr", GBR.replace(LPD, "%IPPOS*%\n" + LPD), "clear.export.json")
film("film-gbr-polarity-twice.gbr", GBR.replace(NEGATIVE, NEGATIVE + POSITIVE), "clear.export.json")
film("film-gbr-polarity-unknown.gbr", GBR.replace(NEGATIVE, "%TF.FilePolarity,Inverted*%\n"),
     "clear.export.json")

# ---------------------------------------------------------------- files that expand in check
# 300,000 explicit offsets (repetition type 4) reused by 10 more records: 3.3 million squares
# from a 300 KB file, charged at what each ring costs through the check
rep_300k = b"\x04" + oas_uint(300000 - 2) + oas_uint(20) * (300000 - 1)
write("layout-repetition-300k-entries.oas",
      start + cell + RECT_HEAD + rep_300k + b"\x14\x04\x00" * 10 + end)
# GDSII: one square cell placed by a 1000 x 1000 AREF (a million rings from 200 bytes)
gds_head = [r for r in gds_records(GDS)[:4]]  # HEADER, BGNLIB, LIBNAME, UNITS
assert [r[0] for r in gds_head] == [0x00, 0x01, 0x02, 0x03]
bgnstr = next(r for r in gds_records(GDS) if r[0] == 0x05)
square = struct.pack(">10i", 0, 0, 1000, 0, 1000, 1000, 0, 1000, 0, 0)
aref_xy = struct.pack(">6i", 0, 0, 2000 * 1000, 0, 0, 2000 * 1000)
write("layout-gds-aref-expands.gds", gds_bytes(gds_head + [
    bgnstr, (0x06, 6, b"HOLE"), (0x08, 0, b""), (0x0D, 2, b"\0\1"), (0x0E, 2, b"\0\0"),
    (0x10, 3, square), (0x11, 0, b""), (0x07, 0, b""),
    bgnstr, (0x06, 6, b"TOP\0"), (0x0B, 0, b""), (0x12, 6, b"HOLE"),
    (0x13, 2, struct.pack(">2h", 1000, 1000)), (0x10, 3, aref_xy), (0x11, 0, b""),
    (0x07, 0, b""), (0x04, 0, b"")]))

# ---------------------------------------------------------------- layer records the readers refuse
# A BOUNDARY's layer must be stated once (GDSII LAYER and DATATYPE, DXF group 8): a missing,
# repeated, negative or empty one leaves the film's layer to the reading tool.


def gds_layer_variant(name, edit):
    out, done = [], False
    for r in gds_records(GDS):
        if r[0] in (GDS_LAYER, GDS_DATATYPE) and not done:
            replaced = edit(r)
            if replaced is not None:
                done = True
                out.extend(replaced)
                continue
        out.append(r)
    assert done, name
    write(name, gds_bytes(out))


gds_layer_variant("layout-gds-no-layer.gds", lambda r: [] if r[0] == GDS_LAYER else None)
gds_layer_variant("layout-gds-no-datatype.gds", lambda r: [] if r[0] == GDS_DATATYPE else None)
gds_layer_variant("layout-gds-layer-twice.gds",
                  lambda r: [r, (GDS_LAYER, 2, b"\0\2")] if r[0] == GDS_LAYER else None)
gds_layer_variant("layout-gds-datatype-twice.gds",
                  lambda r: [r, (GDS_DATATYPE, 2, b"\0\1")] if r[0] == GDS_DATATYPE else None)
gds_layer_variant("layout-gds-negative-layer.gds",
                  lambda r: [(GDS_LAYER, 2, b"\xff\xff")] if r[0] == GDS_LAYER else None)
gds_layer_variant("layout-gds-negative-datatype.gds",
                  lambda r: [(GDS_DATATYPE, 2, b"\x80\x00")] if r[0] == GDS_DATATYPE else None)
write("layout-dxf-layer-twice.dxf",
      DXF.replace("POLYLINE\n" + DXF_ENTITY_LAYER, "POLYLINE\n" + DXF_ENTITY_LAYER + "  8\nOTHER\n", 1))
write("layout-dxf-empty-layer.dxf", DXF.replace(DXF_ENTITY_LAYER, "  8\n\n", 1))
write("layout-dxf-blank-layer.dxf", DXF.replace(DXF_ENTITY_LAYER, "  8\n   \n", 1))
# ---------------------------------------------------------------- fifth round: decode and calibrate
# PSF stacks whose planes are one plane given twice (distances within 1e-6 of each other, in or
# out of order), and a PSF name with an escaped NUL (the system would open its prefix).
psf_stack("psf-stack-float-step.json", [(0.5, "psf-stack-ok.tiff"),
                                        (math.nextafter(0.5, 1.0), "psf-stack-ok.tiff")])
psf_stack("psf-stack-near-unordered.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "psf-stack-ok.tiff"),
                                            (2.0, "psf-stack-ok.tiff"),
                                            (0.5000002, "psf-stack-ok.tiff")])
psf_stack("psf-stack-near-far.json", [(1000.0, "psf-stack-ok.tiff"),
                                      (1000.0009, "psf-stack-ok.tiff")])
psf_stack("psf-stack-nul-path.json", [(0.5, "psf-stack-ok.tiff"),
                                      (1.0, "psf-stack-ok.tiff\u0000.missing")])
psf_stack("psf-stack-nul-only.json", [(0.5, "psf-stack-ok.tiff"), (1.0, "\u0000")])

# Capture files of the wrong kind for a decode or a calibration: npy dtypes that are not light
# values, channel counts other than 1 and 3, shapes of other ranks, a header whose data length
# disagrees; TIFF and PNG layouts the readers do not take. (An alpha channel or other extra
# samples are dropped by design, core/image/tiff_io and png_io: not listed here.)
for stem, descr in [("complex", "<c8"), ("bool", "|b1"), ("object", "|O"), ("unicode", "<U4"),
                    ("half", "<f2"), ("datetime", "<M8[s]"), ("bytes", "|S4"),
                    ("struct", "[('a', '<f4')]")]:
    write("capture-dtype-%s.npy" % stem, npy((28, 28), descr=descr, data=b"\0" * (28 * 28 * 16)))
f4 = lambda n, v=0.5: struct.pack("<%df" % n, *([v] * n))
write("capture-channels-2.npy", npy((28, 28, 2), data=f4(28 * 28 * 2)))
write("capture-channels-4.npy", npy((28, 28, 4), data=f4(28 * 28 * 4)))
write("capture-rank-1.npy", npy((784,), data=f4(784)))
write("capture-rank-4.npy", npy((1, 28, 28, 1), data=f4(784)))
write("capture-rank-0.npy", npy((), data=f4(1)))
write("capture-shape-zero.npy", npy((0, 28), data=b""))
write("capture-trailing-bytes.npy", npy((28, 28), data=f4(784) + b"\0" * 4096))
write("capture-one-pixel.npy", npy((1, 1), data=f4(1)))
write("capture-header-not-dict.npy", b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) +
      b"[1, 2, 3]".ljust(117) + b"\n" + f4(784))
write("capture-header-no-descr.npy", b"\x93NUMPY\x01\x00" + struct.pack("<H", 118) +
      b"{'fortran_order': False, 'shape': (28, 28), }".ljust(117) + b"\n" + f4(784))
write("capture-version-9.npy", b"\x93NUMPY\x09\x00" + npy((28, 28), data=f4(784))[8:])


def tiff_tags(width, height, data, tags):
    """A little-endian TIFF of one strip holding `data`, with the baseline tags replaced or
    added by `tags` {tag: (type, value)} (types 3 SHORT, 4 LONG)."""
    base = {256: (4, width), 257: (4, height), 258: (3, 32), 259: (3, 1), 262: (3, 1),
            273: (4, 8), 277: (3, 1), 278: (4, height), 279: (4, len(data)), 284: (3, 1),
            339: (3, 3)}
    base.update(tags)
    ifd = struct.pack("<H", len(base))
    for tag in sorted(base):
        typ, value = base[tag]
        ifd += struct.pack("<HHII", tag, typ, 1, value) if typ == 4 else struct.pack(
            "<HHIHH", tag, typ, 1, value, 0)
    ifd += struct.pack("<I", 0)
    return b"II*\0" + struct.pack("<I", 8 + len(data)) + data + ifd


write("capture-tiff-complex.tiff", tiff_tags(28, 28, f4(28 * 28 * 2), {258: (3, 64), 339: (3, 6)}))
write("capture-tiff-float16.tiff", tiff_tags(28, 28, b"\0" * (28 * 28 * 2), {258: (3, 16)}))
write("capture-tiff-12-bit.tiff", tiff_tags(28, 28, b"\0" * (28 * 42), {258: (3, 12), 339: (3, 1)}))
write("capture-tiff-strip-short.tiff", tiff_tags(28, 28, f4(28 * 14), {279: (4, 28 * 28 * 4)}))
write("capture-tiff-lzw-garbage.tiff", tiff_tags(28, 28, b"\xff" * 64, {259: (3, 5)}))


def png_rows(width, height, colour, bit_depth, row_bytes, interlace=0):
    """A PNG of `height` rows of `row_bytes` zero bytes each (filter 0)."""
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour, 0, 0, interlace)
    idat = zlib.compress((b"\0" + b"\x40" * row_bytes) * height)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", idat) +
            png_chunk(b"IEND", b""))


write("capture-png-palette-no-plte.png", png_rows(28, 28, 3, 8, 28))
write("capture-png-bit-depth-3.png", png_rows(28, 28, 0, 3, 11))
write("capture-png-rgb-bit-depth-4.png", png_rows(28, 28, 2, 4, 42))


# A point-source capture of {mask} (fuzz/corpus/mask_json/small.mask.json: 7 x 7 cells of 4 px,
# pinholes at cells (1, 0), (3, 6), (5, 0)): Gaussian spots (sigma 1.6 px, peak 800) on a
# background of 20, as float32; clipped at half its peak, a flat top of 36 pixels a float file
# does not declare. Also scaled far beyond any unit (1e300, float64) and below (1e-30), and a
# 16-bit PNG whose spots reach its largest count (65535).
def point_capture(scale=1.0, clip=None):
    values = []
    for r in range(28):
        for c in range(28):
            v = 20.0
            for (pr, pc) in [(1, 0), (3, 6), (5, 0)]:
                dy, dx = r - (4 * pr + 1.5), c - (4 * pc + 1.5)
                v += 800.0 * math.exp(-(dy * dy + dx * dx) / (2 * 1.6 ** 2))
            values.append(struct.unpack("<f", struct.pack("<f", v * scale))[0])
    if clip is not None:
        level = struct.unpack("<f", struct.pack("<f", clip * max(values)))[0]
        values = [min(v, level) for v in values]
    return values


write("capture-point-clipped.npy", npy((28, 28), data=struct.pack("<784f", *point_capture(clip=0.5))))
write("capture-point-clipped.tiff", tiff(28, 28, values=point_capture(clip=0.5)))
write("capture-point-1e300.npy", npy((28, 28), descr="<f8",
                                     data=struct.pack("<784d", *[v * 1e300 for v in point_capture()])))
write("capture-point-1e-30.npy", npy((28, 28), data=struct.pack("<784f", *point_capture(1e-30))))
rows16 = b""
for r, row in enumerate(zip(*[iter(point_capture(200.0, clip=0.5))] * 28)):
    rows16 += b"\0" + b"".join(struct.pack(">H", min(65535, int(v))) for v in row)
write("capture-point-saturated-16.png", png(28, 28, zlib.compress(rows16), bit_depth=16))
# ---------------------------------------------------------------- capture and PSF sampling
# The valid RAW capture fuzz/corpus/raw/small.dng ({raw_capture}) reads as 16 x 12 (2 x 2 Bayer
# blocks of its 32 x 24 sensor): a float PSF at the sensor's full resolution, a PSF of neither
# size, a grey mosaic saved as TIFF and a colour image saved as .npy.
sensor_psf = [0.0] * (32 * 24)
sensor_psf[3 * 32 + 5] = 1.0
sensor_psf[10 * 32 + 20] = 0.5
write("psf-sensor-32x24.tiff", tiff(32, 24, values=sensor_psf))
write("psf-40x30.tiff", tiff(40, 30, values=[1.0 / 1200] * 1200))
write("capture-mosaic-32x24.tiff", tiff(32, 24, values=[0.5] * 768))
write("capture-rgb.npy", npy((24, 32, 3), descr="<f8", data=struct.pack("<2304d", *[0.5] * 2304)))
