"""`check` of a DXF reads what a viewer would draw: an exported drawing edited by an independent
DXF library (ezdxf, Debian's python3-ezdxf) with a layer turned off or frozen, a polyline width
or a mirrored extrusion is refused by name, never reported clean; the unedited round trip through
ezdxf stays clean, and a file that states no unit is read as micrometres with a warning."""
import json
import shutil

import pytest

ezdxf = pytest.importorskip("ezdxf", reason="python3-ezdxf is not installed")


def first_entity(doc):
    return next(iter(doc.modelspace()))


def turn_off(doc):
    doc.layers.get(first_entity(doc).dxf.layer).off()


def freeze(doc):
    doc.layers.get(first_entity(doc).dxf.layer).freeze()


def widen(doc):
    e = first_entity(doc)
    e.dxf.default_start_width = 300
    e.dxf.default_end_width = 300


def mirror(doc):
    first_entity(doc).dxf.extrusion = (0, 0, -1)


VARIANTS = [("layer off", turn_off, "which is off"),
            ("layer frozen", freeze, "which is frozen"),
            ("polyline width 300", widen, "width 300"),
            ("negative extrusion", mirror, "negative extrusion")]


@pytest.fixture
def exported(cli, tmp_path):
    cli.run("generate", "--family", "random", "--grid", "16", "--holes", "20", "--spacing", "2",
            "--tiles", "2", "--seed", "7", "-o", "m.mask.json")
    cli.run("export", "m.mask.json", "--format", "dxf", "--no-psf", "-o", "e")
    return tmp_path / "e"


def save_variant(exported, name, edit):
    """The export edited by ezdxf, saved as NAME.dxf with the export's sidecar beside it."""
    doc = ezdxf.readfile(str(exported / "m.dxf"))
    edit(doc)
    doc.saveas(str(exported / f"{name}.dxf"))
    side = json.loads((exported / "m.export.json").read_text())
    text = json.dumps(side).replace("m.dxf", f"{name}.dxf")
    (exported / f"{name}.export.json").write_text(text)
    return f"e/{name}.dxf"


def test_ezdxf_round_trip_stays_clean(cli, exported):
    path = save_variant(exported, "same", lambda doc: None)
    # Exit 0; exported without a vendor, so the verdict says no design rules were checked.
    assert "no design rules given: none checked" in cli.run("check", path).stdout


def test_styling_a_viewer_honours_is_refused(cli, exported):
    for i, (name, edit, fragment) in enumerate(VARIANTS):
        path = save_variant(exported, f"v{i}", edit)
        message = cli.error("check", path)
        assert fragment in message, (name, message)


def test_a_dxf_without_units_is_read_as_micrometres_with_a_warning(cli, exported):
    # The writer's unit statements removed: $INSUNITS 0 and no pinmask units= comment.
    text = (exported / "m.dxf").read_text()
    lines = text.split("\n")
    for i, line in enumerate(lines):
        if line.strip() == "$INSUNITS":
            lines[i + 2] = "0"
    text = "\n".join(lines).replace("units=um", "")
    shutil.copy(exported.parent / "m.mask.json", exported / "n.mask.json")
    (exported / "n.dxf").write_text(text)
    p = cli.run("check", "e/n.dxf", "--mask", "e/n.mask.json", expect=(0, 1))
    assert "states no unit" in p.stderr and "read as um" in p.stderr, p.stderr
    assert "read as um" in p.stdout
