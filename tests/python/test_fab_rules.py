"""check() takes the vendor rules from the export sidecar, as `pinmask check` does; vendor,
min_space (alias min_gap) and min_feature override them."""
import pytest

import pinmask


def test_check_takes_the_vendor_rules_from_the_sidecar(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the sidecar records the mask path as given to export
    cli.run("generate", "--seed", "3", "-o", "m.mask.json")
    cli.run("export", "m.mask.json", "--vendor", "chrome-photomask", "--min-feature", "2um",
            "-o", "fab")
    gds = str(tmp_path / "fab" / "m.gds")
    j = pinmask.check(gds)
    assert j["clean"], j["violations"]
    assert j["vendor"] == "chrome" and j["rules_from"] == "the export sidecar"
    assert j["rules"]["min_feature_um"] == pytest.approx(2.0)
    assert j["rules"]["min_gap_um"] == pytest.approx(1.0)
    # The same answers as the command line.
    import json
    cj = json.loads(cli.run("check", "fab/m.gds", "--json").stdout)
    assert cj["rules"] == j["rules"] and cj["vendor"] == j["vendor"]
    film = pinmask.check(gds, vendor="film-plotter")
    assert film["vendor"] == "film" and film["rules"]["min_gap_um"] == pytest.approx(16.0)
    wide = pinmask.check(gds, min_space="500um")  # pinholes two cells apart: 440 um apart
    assert wide["rules"]["min_gap_um"] == pytest.approx(500.0)
    assert not wide["clean"] and wide["counts"].get("gap", 0) > 0
    with pytest.raises(ValueError, match="min_space"):
        pinmask.check(gds, min_space="2um", min_gap="2um")
