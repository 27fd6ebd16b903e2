"""`check` of an SVG reads what a renderer would draw: every styling construct that changes
rsvg-convert's rendering of an exported drawing (an independent renderer, librsvg) is refused by
name, never reported "identical to the design ... clean". The drawing is pinmask's own export;
each variant changes one thing in it."""
import shutil
import struct
import subprocess
import zlib

import pytest

RSVG = shutil.which("rsvg-convert")

# (name, text of the exported drawing, replacement, fragment of check's message)
PATTERN = '<g id="pattern" fill="#000000" stroke="none">'
FIRST_PATH = '<path d="M'
VARIANTS = [
    ("display none", FIRST_PATH, '<path display="none" d="M', "attribute 'display'"),
    ("visibility hidden", FIRST_PATH, '<path visibility="hidden" d="M', "attribute 'visibility'"),
    ("opacity 0", PATTERN, PATTERN.replace("<g ", '<g opacity="0" '), "attribute 'opacity'"),
    ("fill-opacity 0", PATTERN, PATTERN.replace("<g ", '<g fill-opacity="0" '),
     "attribute 'fill-opacity'"),
    ("white fill", PATTERN, PATTERN.replace("#000000", "#ffffff"), "a white shape"),
    ("red fill", PATTERN, PATTERN.replace("#000000", "#ff0000"), 'fill="#ff0000"'),
    ("one white path", FIRST_PATH, '<path fill="white" d="M', "a white shape"),
    ("DOCTYPE sets fill none", "<svg ",
     '<!DOCTYPE svg [<!ATTLIST path fill CDATA "none">]>\n<svg ', "markup declaration"),
    ("nested svg scaled 2x", PATTERN + "{body}</g>\n",
     '<svg viewBox="{vb}" width="{w2}" height="{w2}">' + PATTERN + "{body}</g>\n</svg>\n",
     "nested <svg>"),
    ("300 um stroke", PATTERN,
     PATTERN.replace('stroke="none"', 'stroke="#000000" stroke-width="300"'), 'stroke="#000000"'),
    ("clip-path", PATTERN,
     '<clipPath id="c"><rect x="0" y="0" width="1" height="1"/></clipPath>'
     + PATTERN.replace("<g ", '<g clip-path="url(#c)" '), "clipPath"),
    ("stylesheet", "<svg ",
     '<?xml-stylesheet type="text/css" href="data:text/css,path%7Bfill:none%7D"?>\n<svg ',
     "processing instruction"),
]


def png_pixels(data):
    """The decompressed IDAT stream of a PNG: equal for equal images from one encoder."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        if kind == b"IDAT":
            idat += data[pos + 8:pos + 8 + n]
        pos += 12 + n
    return zlib.decompress(idat)


def render(svg_path):
    p = subprocess.run([RSVG, "-w", "400", "-h", "400", "-b", "white", "-f", "png", str(svg_path)],
                       capture_output=True, timeout=120)
    assert p.returncode == 0, p.stderr
    return png_pixels(p.stdout)


@pytest.mark.skipif(RSVG is None, reason="rsvg-convert (librsvg2-bin) is not installed")
def test_every_styling_construct_that_changes_rendering_is_refused(cli, tmp_path):
    cli.run("generate", "--family", "random", "--grid", "16", "--holes", "20", "--spacing", "2",
            "--tiles", "2", "--seed", "7", "-o", "m.mask.json")
    cli.run("export", "m.mask.json", "--format", "svg", "--no-psf", "-o", "e")
    clean = (tmp_path / "e" / "m.svg").read_text()
    # Exit 0; exported without a vendor, so the verdict says no design rules were checked.
    assert "no design rules given: none checked" in cli.run("check", "e/m.svg").stdout
    root = clean[clean.index("<svg "):clean.index(">", clean.index("<svg "))]
    vb = root.split('viewBox="')[1].split('"')[0]
    width = float(vb.split()[2])
    reference = render(tmp_path / "e" / "m.svg")
    start = clean.index(PATTERN) + len(PATTERN)
    body = clean[start:clean.index("</g>", start)]
    for name, old, new, fragment in VARIANTS:
        old = old.replace("{body}", body)
        assert old in clean, name
        new = new.replace("{body}", body).replace("{vb}", vb).replace("{w2}", f"{2 * width:g}")
        text = clean.replace(old, new, 1)
        path = tmp_path / "e" / "v.svg"
        path.write_text(text)
        # The independent renderer draws something else than the design ...
        assert render(path) != reference, f"{name}: rsvg-convert draws it as the design"
        # ... and check refuses it, naming the construct (exit 2, not "clean").
        message = cli.error("check", "e/v.svg", "--mask", "m.mask.json")
        assert fragment in message, (name, message)
