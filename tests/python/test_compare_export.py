"""Compare report, export and check: the module against `pinmask compare/export/check`."""
import json
import pathlib

import numpy as np

import pytest

import pinmask


def test_compare_report_and_rows(tmp_path, mask7):
    other = pinmask.generate(seed=8)
    out = pinmask.compare([mask7, other], report=str(tmp_path / "r.pdf"), tv_iterations=30)
    assert out["report"] == [str(tmp_path / "r.pdf")]
    assert (tmp_path / "r.pdf").read_bytes()[:5] == b"%PDF-"
    assert [r["geometry_hash"] for r in out["masks"]] == [mask7.geometry_hash(),
                                                        other.geometry_hash()]
    assert out["masks"][0]["analytic_wiener_psnr_db"] == pinmask.metrics(
        mask7, tv_iterations=30)["analytic_wiener_psnr_db"]


def test_compare_with_baselines_equals_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "--baselines", "--baseline-count", "3",
                           "--tv-iters", "20", "--json").stdout)
    out = pinmask.compare([str(tmp_path / "m.mask.json")], baselines=True, baseline_count=3,
                          tv_iterations=20)
    assert [r["kind"] for r in out["masks"]] == [m["kind"] for m in j["masks"]]
    for row, cli_row in zip(out["masks"], j["masks"]):
        assert row["geometry_hash"] == cli_row["geometry_hash"]
        assert row["sim_wiener_psnr_db"] == cli_row["sim_wiener_psnr_db"]


def test_compare_refuses_two_cameras(mask7):
    other = pinmask.generate(seed=8, camera=pinmask.Camera(object_distance_m=3.0))
    with pytest.raises(ValueError, match="one camera"):
        pinmask.compare([mask7, other])


def test_export_same_bytes_as_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", "--format", "svg,gds,dxf,gerber,png", "--marks", "--label",
            "--frame", "1mm", "--no-psf", "-o", "cli")
    out = pinmask.export_mask(str(tmp_path / "m.mask.json"), str(tmp_path / "py"),
                              formats=["svg", "gds", "dxf", "gerber", "png"], marks=True,
                              label=True, frame="1mm")
    assert len(out["files"]) == 5
    for f in out["files"]:
        name = f["name"]
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
        if f["format"] != "png":
            assert f["verification"].startswith("read back")
    lay = pinmask.layout(mask7, marks=True, label="m", frame="1mm")
    assert pinmask.fabrication_bytes(lay, "gds") == (tmp_path / "cli" / "m.gds").read_bytes()
    assert len(lay.polygons) == 80  # 20 pinholes x 2 x 2 tiles
    assert lay.polygons[0].shape[1] == 2


def test_check_equals_cli_json(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    pinmask.export_mask(mask7, str(tmp_path / "fab"), formats=["gds"], stem="m")
    for args, kwargs in [((str(tmp_path / "m.mask.json"),), {}),
                         ((str(tmp_path / "fab" / "m.gds"),), {}),
                         ((str(tmp_path / "fab" / "m.gds"), "--mask",
                           str(tmp_path / "m.mask.json")),
                          {"mask": str(tmp_path / "m.mask.json")}),
                         ((str(tmp_path / "m.mask.json"), "--vendor", "chrome",
                           "--min-gap", "600um"), {"vendor": "chrome", "min_gap": "600um"})]:
        p = cli.run("check", *args, "--json", expect=0 if "min_gap" not in kwargs else 1)
        j = json.loads(p.stdout)
        got = json.loads(json.dumps(pinmask.check(args[0], **kwargs)))
        assert got == j, args


def test_check_and_export_errors(tmp_path, mask7):
    with pytest.raises(ValueError, match="^formats = oasis2"):
        pinmask.export_mask(mask7, str(tmp_path / "x"), formats=["oasis2"])
    with pytest.raises(ValueError, match="input"):
        pinmask.check(str(tmp_path / "none.gds"))
    with pytest.raises(ValueError, match="vendor"):
        pinmask.check(mask7, vendor="moon")


def test_export_new_formats_same_bytes_as_cli(cli, tmp_path, mask7):
    """OASIS (read back before commit) and 1-bit TIFF through the same export pipeline."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", "--format", "oasis,tiff1", "--no-psf", "-o", "cli")
    out = pinmask.export_mask(str(tmp_path / "m.mask.json"), str(tmp_path / "py"),
                              formats=["oasis", "tiff1"])
    assert [f["format"] for f in out["files"]] == ["oasis", "tiff1"]
    for f in out["files"]:
        name = f["name"]
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert out["files"][0]["verification"].startswith("read back")
    assert pinmask.check(str(tmp_path / "py" / "m.oas"), mask=mask7)["comparison"]["ok"]


@pytest.mark.parametrize("cli_args,kwargs", [
    (["--format", "dxf,gds", "--units", "mm"], dict(formats=["dxf", "gds"], units="mm")),
    (["--format", "dxf,gerber", "--shape", "circle", "--circles", "native", "--kerf", "20um"],
     dict(formats=["dxf", "gerber"], shape="circle", circles="native", kerf="20um")),
    (["--format", "gds,svg", "--hierarchy", "cells", "--emulsion", "down", "--draw", "film"],
     dict(formats=["gds", "svg"], hierarchy="cells", emulsion="down", draw="film")),
])
def test_export_units_and_drawing_equal_cli(cli, tmp_path, mask7, cli_args, kwargs):
    """Export's units, emulsion, drawing, circles, hierarchy, kerf and snap bound: the same
    bytes as the command's flags (the DXF in mm is the case a shop asks for)."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", *cli_args, "--no-psf", "-o", "cli")
    out = pinmask.export_mask(str(tmp_path / "m.mask.json"), str(tmp_path / "py"), **kwargs)
    names = sorted(p.name for p in (tmp_path / "cli").iterdir() if p.suffix != ".json")
    assert names == sorted(f["name"] for f in out["files"])
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # The settings are used: without them the files differ.
    default = pinmask.export_mask(str(tmp_path / "m.mask.json"), str(tmp_path / "default"),
                                  formats=kwargs["formats"])
    assert any((tmp_path / "default" / f["name"]).read_bytes() !=
               (tmp_path / "py" / f["name"]).read_bytes() for f in default["files"])


def test_export_max_snap_error_refuses_as_cli(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    msg = cli.error("export", "m.mask.json", "--format", "tiff1", "--dpi", "1000",
                    "--max-snap-error", "1nm", "--no-psf", "-o", "cli")
    with pytest.raises(ValueError) as e:
        pinmask.export_mask(mask7, str(tmp_path / "py"), formats=["tiff1"], dpi=1000,
                            max_snap_error="1nm")
    assert str(e.value) == msg.replace("--max-snap-error", "max_snap_error").replace("--dpi",
                                                                                     "dpi")
    assert not (tmp_path / "py").exists() or not any((tmp_path / "py").iterdir())


def test_export_sidecar_equals_cli_and_check_reads_it(cli, tmp_path, mask7, monkeypatch):
    """export_mask writes <stem>.export.json as `pinmask export` does (without PSF files, as
    --no-psf), and check() of a Python export reads its settings from it."""
    mask7.save(str(tmp_path / "m.mask.json"))
    args = dict(formats=["gds", "dxf"], tone="dark", shape="circle", units="mm", frame="1mm")
    cli.run("export", "m.mask.json", "--format", "gds,dxf", "--tone", "dark", "--shape",
            "circle", "--units", "mm", "--frame", "1mm", "--no-psf", "-o", "cli")
    monkeypatch.chdir(tmp_path)  # the mask path recorded as given, as the command records it
    out = pinmask.export_mask("m.mask.json", "py", psf=False, **args)
    assert out.psf.startswith("not written")
    py_side = json.loads((tmp_path / "py" / "m.export.json").read_text())
    cli_side = json.loads((tmp_path / "cli" / "m.export.json").read_text())
    assert py_side == cli_side == out.to_dict()
    # check() of the Python export uses the sidecar's tone, shape, frame and units: clean, the
    # same report as the command's check of the same file.
    report = pinmask.check("py/m.gds", mask="m.mask.json")
    cli_report = json.loads(cli.run("check", "py/m.gds", "--mask", "m.mask.json",
                                    "--json").stdout)
    for key in ["clean", "settings", "rules_from", "tone", "polygons", "annotations"]:
        assert report[key] == cli_report[key], key
    assert report["clean"] and report["settings"] == "from py/m.export.json"
    # Without the sidecar the defaults (film rules, squares, no frame) do not fit the file.
    bare = pinmask.check("py/m.gds", mask="m.mask.json", no_sidecar=True)
    assert not bare["clean"] and bare["polygons"] != report["polygons"]


def test_export_psf_files_equal_cli(cli, tmp_path, mask7, monkeypatch):
    """The PSF files beside the layouts (the default, and npy=True as --npy): the same bytes as
    the command's, the same export sidecar, and decode reads the PSF written."""
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("export", "m.mask.json", "--format", "gds", "--npy", "-o", "cli")
    monkeypatch.chdir(tmp_path)
    out = pinmask.export_mask("m.mask.json", "py", formats=["gds"], npy=True)
    assert sorted(out.psf.files) == ["m.psf.json", "m.psf.npy", "m.psf.tiff"]
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir())
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    np.testing.assert_allclose(np.load("py/m.psf.npy"), pinmask.psf(mask7), rtol=1e-6, atol=0)
    with pytest.raises(ValueError, match="npy writes the PSF as .npy: it needs psf=True"):
        pinmask.export_mask("m.mask.json", "py2", formats=["gds"], psf=False, npy=True)


def test_export_never_writes_over_its_mask_file(tmp_path, mask7, monkeypatch):
    """A mask file whose name an output takes (m.psf.json: the PSF sidecar of stem m) is
    refused before any file is written, as the command's output plan refuses it."""
    monkeypatch.chdir(tmp_path)
    mask7.save("m.psf.json")
    before = (tmp_path / "m.psf.json").read_bytes()
    with pytest.raises(ValueError, match="stem = m: would write m.psf.json over the mask file"):
        pinmask.export_mask("m.psf.json", ".", formats=["svg"], stem="m")
    assert (tmp_path / "m.psf.json").read_bytes() == before
    assert not (tmp_path / "m.svg").exists()
