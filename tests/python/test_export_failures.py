"""A failed export leaves nothing: export_mask() whose design-rule check finds violations raises
RuntimeError naming the failed rule and writes no file (no temporary either), as `pinmask export`
exits 1 with an empty folder; write_on_violations=True writes the files for inspection."""
import pathlib

import pytest

import pinmask

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
MASK = str(SOURCE_DIR / "fuzz" / "corpus" / "mask_json" / "small.mask.json")


@pytest.mark.parametrize("args, rule", [
    (dict(vendor="laser-cutter", min_feature="1m"), "feature"),
    (dict(vendor="chrome-photomask", min_space="2mm"), "gap"),
    (dict(vendor="film", formats=["gds", "oasis"], min_feature="500um"), "feature"),
])
def test_a_failed_design_rule_check_writes_nothing(tmp_path, cli, args, rule):
    out = tmp_path / "py"
    with pytest.raises(RuntimeError, match="found violations: " + rule) as e:
        pinmask.export_mask(MASK, str(out), **args)
    assert "write_on_violations" in str(e.value)  # the keyword, in Python's spelling
    assert not out.exists() or list(out.iterdir()) == []
    # The command line: exit 1, the same rule, an empty folder.
    flags = []
    for k, v in args.items():
        flag = "--format" if k == "formats" else "--" + k.replace("_", "-")
        flags += [flag, ",".join(v) if isinstance(v, list) else v]
    p = cli.run("export", MASK, *flags, "-o", "cli", expect=1)
    assert "found violations: " + rule in p.stderr
    assert "--write-on-violations" in p.stderr
    cli_out = tmp_path / "cli"
    assert not cli_out.exists() or list(cli_out.iterdir()) == []


def test_write_on_violations_writes_the_files_for_inspection(tmp_path):
    out = pinmask.export_mask(MASK, str(tmp_path / "fab"), vendor="laser-cutter", formats=["dxf"],
                              min_feature="1m", write_on_violations=True)
    assert not out["drc"]["clean"] and out["drc"]["counts"]["feature"] > 0
    names = sorted(p.name for p in (tmp_path / "fab").iterdir())
    assert names == ["small.dxf", "small.export.json", "small.psf.json", "small.psf.tiff"]
    with pytest.raises(ValueError, match="write_on_violations"):
        pinmask.export_mask(MASK, str(tmp_path / "both"), vendor="laser-cutter",
                            require_drc_clean=True, write_on_violations=True)
    assert not (tmp_path / "both").exists()
