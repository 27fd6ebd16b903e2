"""Exported files open at the size the export says: KLayout (read with the DXF unit the export
note names) and ezdxf (reading $INSUNITS) agree on every DXF's size, and KLayout reads the GDSII
of the same export at the same scale. KLayout's DXF reader ignores $INSUNITS, so without the
note's unit a millimetre DXF opens 1000x too small: the note is what makes the file usable.
Skipped, with the reason, where `klayout` or ezdxf is not installed.
"""
import json
import pathlib
import re
import shutil
import subprocess

import pytest

ezdxf = pytest.importorskip("ezdxf", reason="ezdxf (Debian python3-ezdxf) is not installed")
from ezdxf import bbox as ezdxf_bbox  # noqa: E402

KLAYOUT = shutil.which("klayout")

# $INSUNITS -> metres per drawing unit (AutoCAD's codes: 1 inch, 4 mm, 13 micron).
INSUNITS_M = {1: 0.0254, 4: 1e-3, 13: 1e-6}

# One KLayout run reads every file (each start costs seconds): [path, dxf unit or None] in,
# [width_um, height_um] per file out.
KLAYOUT_SCRIPT = """
import json, pya
out = []
for path, unit in json.load(open(files)):
    opt = pya.LoadLayoutOptions()
    if unit is not None:
        opt.dxf_unit = float(unit)
    ly = pya.Layout()
    ly.read(path, opt)
    box = pya.DBox()
    for c in ly.top_cells():
        box += c.dbbox()
    out.append([box.width(), box.height()])
print(json.dumps(out))
"""

EXPORTS = [
    ("units-um", ["--units", "um"]),
    ("units-mm", ["--units", "mm"]),
    ("units-in", ["--units", "in"]),
    ("film-plotter", ["--vendor", "film-plotter"]),
    ("laser-cutter", ["--vendor", "laser-cutter", "--shape", "circle"]),
]


def dxf_unit_of(notes):
    for n in notes:
        if n.startswith("the dxf file"):
            m = re.search(r"DXF unit = ([0-9.e+]+)", n)
            assert m, n
            return float(m.group(1))
    raise AssertionError("no note for the dxf file: %r" % notes)


def ezdxf_size_m(path):
    doc = ezdxf.readfile(path)
    per_unit = INSUNITS_M[doc.header["$INSUNITS"]]
    box = ezdxf_bbox.extents(doc.modelspace())
    return box.size.x * per_unit, box.size.y * per_unit


@pytest.mark.skipif(KLAYOUT is None, reason="klayout (Debian klayout) is not installed")
def test_klayout_and_ezdxf_agree_on_every_export_size(cli, tmp_path):
    mask = tmp_path / "m.mask.json"
    cli.run("generate", "--seed", "3", "--grid", "8", "--holes", "6", "-o", str(mask))
    files, sizes = [], []
    for name, flags in EXPORTS:
        out = tmp_path / name
        side = json.loads(cli.run("export", str(mask), "-o", str(out), "--format", "dxf,gds",
                                  "--json", *flags).stdout)
        unit = dxf_unit_of(side["notes"])
        gds_note = [n for n in side["notes"] if n.startswith("the gds file")]
        assert gds_note and "opens it at scale" in gds_note[0]
        dxf = next(out.glob("*.dxf"))
        gds = next(out.glob("*.gds"))
        files += [[str(dxf), unit], [str(gds), None]]
        sizes.append((name, ezdxf_size_m(str(dxf))))
    listing = tmp_path / "files.json"
    listing.write_text(json.dumps(files))
    script = tmp_path / "sizes.py"
    script.write_text(KLAYOUT_SCRIPT)
    run = subprocess.run([KLAYOUT, "-b", "-r", str(script), "-rd", "files=%s" % listing],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    read = json.loads(run.stdout.strip().splitlines()[-1])
    for i, (name, (w_m, h_m)) in enumerate(sizes):
        dxf_um, gds_um = read[2 * i], read[2 * i + 1]
        # KLayout's circles are polygons of its own: a part in 1e3 covers their chord sag; a
        # wrong unit is a factor of 25.4 or more.
        for got, want in ((dxf_um[0], w_m * 1e6), (dxf_um[1], h_m * 1e6)):
            assert got == pytest.approx(want, rel=1e-3), (name, dxf_um, w_m, h_m)
        # The GDSII of the same export holds the same drawing (and may hold more around it),
        # at the same scale: a wrong unit would be 1000x off.
        for g, d in zip(gds_um, dxf_um):
            assert d * (1 - 1e-3) <= g <= 2 * d, (name, gds_um, dxf_um)
        assert w_m > 1e-3  # an 8 x 8 cell pattern of a few hundred um cells, tiled
