"""Values the command line refuses, refused by Python with ValueError naming the keyword: sides
with a shape that has none (export_mask, layout, check), and an LSI tolerance below a millionth
of a pixel (a denormal such as 1e-320) or above 1000 px."""
import pathlib

import pytest

import pinmask

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
MASK = str(SOURCE_DIR / "fuzz" / "corpus" / "mask_json" / "small.mask.json")


@pytest.mark.parametrize("shape", ["square", "circle"])
def test_sides_with_a_shape_without_sides_is_refused(tmp_path, cli, shape):
    with pytest.raises(ValueError, match="^sides = 3: sets the sides of shape polygon"):
        pinmask.export_mask(MASK, str(tmp_path / "e"), shape=shape, sides=3)
    assert not (tmp_path / "e").exists()
    with pytest.raises(ValueError, match="^sides = 3"):
        pinmask.layout(MASK, shape=shape, sides=3)
    with pytest.raises(ValueError, match="^sides = 3: sets the sides of shape polygon"):
        pinmask.check(MASK, shape=shape, sides=3)
    # the command line says the same with its flags
    assert "--sides = 3: sets the sides of --shape polygon" in cli.error(
        "export", MASK, "--shape", shape, "--sides", "3", "-o", "e")
    assert "--sides = 3" in cli.error("check", MASK, "--shape", shape, "--sides", "3")
    # with the polygon shape the value is used
    assert pinmask.layout(MASK, shape="polygon", sides=3).polygons[0].shape == (3, 2)


@pytest.mark.parametrize("t", [1e-320, 5e-324, 1e-7, 1000.5, float("inf"), float("nan"), 0.0])
def test_lsi_tolerance_outside_its_range_is_refused_like_the_command_line(cli, t):
    with pytest.raises(ValueError, match="^lsi_tolerance_px = .*must be between 1e-6 and 1000 px"):
        pinmask.optics(lsi_tolerance_px=t)
    assert "must be between 1e-6 and 1000 px" in cli.error("design", "--lsi-tolerance", repr(t))


def test_the_ends_of_the_lsi_tolerance_range_are_accepted():
    for t in (1e-6, 1000.0):
        assert pinmask.optics(lsi_tolerance_px=t)["lsi_tolerance_px"] == t


@pytest.mark.parametrize("vendor", ["none", "film-plotter", "gerber-film", "chrome-photomask"])
def test_formats_default_to_the_vendor_presets_as_the_command(tmp_path, cli, vendor):
    out = pinmask.export_mask(MASK, str(tmp_path / "py"), vendor=vendor)
    cli.run("export", MASK, "--vendor", vendor, "-o", "cli")
    py_names = sorted(p.name for p in (tmp_path / "py").iterdir())
    assert py_names == sorted(p.name for p in (tmp_path / "cli").iterdir())
    for name in py_names:
        if not name.endswith(".export.json"):  # the sidecar records the call's own input
            assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert len(out["files"]) == len([n for n in py_names if ".psf." not in n]) - 1
