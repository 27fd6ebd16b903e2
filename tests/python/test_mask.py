"""Masks: generate/load/save against `pinmask generate` (same seed, same bytes)."""
import json

import numpy as np
import pytest

import pinmask


@pytest.mark.parametrize("args,kwargs", [
    (["--family", "random", "--grid", "16", "--holes", "20", "--spacing", "2", "--tiles", "2",
      "--seed", "7"], dict(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=7)),
    (["--family", "paper", "--seed", "3"], dict(family="paper", seed=3)),
    (["--family", "mura", "--grid", "13", "--allow-violations"],
     dict(family="mura", grid=13, allow_violations=True)),
    (["--family", "random", "--grid", "24", "--holes", "30", "--seed", "11", "--pinhole",
      "300um", "--kernel", "box"],
     dict(family="random", grid=24, holes=30, seed=11, camera=pinmask.Camera(pinhole_m="300um"),
          kernel="box")),
])
def test_generate_same_bytes_as_cli(cli, tmp_path, args, kwargs):
    cli.run("generate", *args, "-o", "cli.mask.json")
    mask = pinmask.generate(**kwargs)
    assert mask.to_json() == (tmp_path / "cli.mask.json").read_text()
    mask.save(str(tmp_path / "py.mask.json"))
    assert (tmp_path / "py.mask.json").read_bytes() == (tmp_path / "cli.mask.json").read_bytes()


def test_load_save_roundtrip(tmp_path, mask7):
    path = str(tmp_path / "m.mask.json")
    pinmask.save_mask(mask7, path)
    back = pinmask.load_mask(path)
    assert back.to_json() == mask7.to_json()
    assert back.geometry_hash() == mask7.geometry_hash()
    assert pinmask.mask_from_json(mask7.to_json()).pattern.pinholes == mask7.pattern.pinholes


def test_geometry_hash_equals_cli(cli, mask7):
    j = json.loads(cli.run("generate", "--seed", "7", "-o", "m.mask.json", "--json").stdout)
    assert j["geometry_hash"] == mask7.geometry_hash()


def test_pattern_occupancy_and_spacing(mask7):
    occ = mask7.pattern.occupancy()
    assert occ.shape == (16, 16) and occ.dtype == np.uint8
    assert occ.sum() == 20
    for r, c in mask7.pattern.pinholes:
        assert occ[r, c] == 1
    assert mask7.pattern.spacing_violations() == []
    # An independent torus check: no two pinholes closer than 2 cells.
    cells = mask7.pattern.pinholes
    for i, (r1, c1) in enumerate(cells):
        for r2, c2 in cells[i + 1:]:
            dr = min(abs(r1 - r2), 16 - abs(r1 - r2))
            dc = min(abs(c1 - c2), 16 - abs(c1 - c2))
            assert dr * dr + dc * dc >= 4


def test_edit_mask_and_validate(mask7):
    p = mask7.pattern
    r, c = p.pinholes[0]
    p.pinholes = p.pinholes + [(r, (c + 1) % 16)]  # a neighbour: breaks the spacing rule
    mask7.pattern = p
    with pytest.raises(ValueError):
        mask7.pattern.validate()
    mask7.pattern.validate(allow_spacing_violations=True)


def test_infeasible_holes_same_message_as_cli(cli):
    msg = cli.error("generate", "--grid", "16", "--holes", "200", "-o", "x.mask.json")
    with pytest.raises(ValueError) as e:
        pinmask.generate(grid=16, holes=200)
    # The same message, naming the keyword where the CLI names its flag.
    assert msg.startswith("--holes = 200: ")
    assert str(e.value) == "holes" + msg[len("--holes"):]


def test_mura_spacing_same_message_as_cli(cli):
    msg = cli.error("generate", "--family", "mura", "--grid", "13", "-o", "x.mask.json")
    with pytest.raises(ValueError) as e:
        pinmask.generate(family="mura", grid=13)
    # The same message, naming the keywords where the CLI names its flags.
    assert "pass --allow-violations" in msg and "lower --spacing" in msg
    assert str(e.value) == msg.replace("--allow-violations", "allow_violations").replace(
        "--spacing", "spacing")


@pytest.mark.parametrize("name", ["mask-unknown-key.mask.json", "mask-wrong-version.mask.json",
                                  "mask-truncated.mask.json", "mask-nan.mask.json",
                                  "mask-spacing-violation.mask.json"])
def test_bad_mask_file_same_message_as_cli(cli, bad_inputs, name):
    path = str(bad_inputs / name)
    msg = cli.error("psf", path, "-o", "psf.tiff")
    with pytest.raises(ValueError) as e:
        pinmask.load_mask(path)
    assert str(e.value) == msg
