#!/usr/bin/python3
"""Writes the malformed camera RAW files of tests/bad-inputs/ (raw-*.dng, raw-*.nef, ...) and the
valid DNG seed of fuzz/corpus/raw/ (deterministic; standard library only).

The seed is a minimal uncompressed DNG: 32 x 24 pixels, 16-bit RGGB CFA, BlackLevel 64,
WhiteLevel 4095, values 64 + (10 r + c) mod 4000. Each bad file breaks it in one way; manifest.txt
says which command reads it and what the message must name (LibRaw's reason, or ours).
"""
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent
FUZZ = HERE.parent.parent / "fuzz" / "corpus" / "raw"

SHORT, LONG, ASCII, BYTE, SRATIONAL = 3, 4, 2, 1, 10


def dng(width=32, height=24, bps=16, compression=1, photometric=32803, cfa=(0, 1, 1, 2),
        magic=b"II*\x00", ifd_offset=None, data_fraction=1.0, black=64, white=4095):
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
    add(271, ASCII, "pinmask")
    add(272, ASCII, "test sensor")
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


def write(name, data):
    (HERE / name).write_bytes(data if isinstance(data, bytes) else data.encode())


FUZZ.mkdir(parents=True, exist_ok=True)
(FUZZ / "small.dng").write_bytes(dng())
write("raw-empty.dng", b"")
write("raw-text.nef", "this is a text file named like a Nikon RAW file\n" * 4)
write("raw-wrong-magic.dng", dng(magic=b"XX*\x00"))
write("raw-zero-width.dng", dng(width=0))
write("raw-tiny.dng", dng(width=8, height=8))
write("raw-giga.dng", dng(width=40000, height=40000))
write("raw-ifd-beyond-eof.dng", dng(ifd_offset=10_000_000))
write("raw-bps-32.dng", dng(bps=32))
write("raw-compression-99.dng", dng(compression=99))
write("raw-white-below-black.dng", dng(black=3000, white=100))
write("raw-huge-truncated.dng", dng(width=6000, height=4000, data_fraction=0.0))
