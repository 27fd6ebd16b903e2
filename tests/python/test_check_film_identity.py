"""check() compares what identifies the film (GDSII/OASIS layer and datatype, DXF layer name,
Gerber polarity) with the export sidecar and the vendor preset, and gives the verdicts of
`pinmask check` on the corpus files that edit an export one way (tests/bad-inputs/film-*)."""
import json
import pathlib

import pytest

import pinmask

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
CORPUS = SOURCE_DIR / "tests" / "bad-inputs"
# (file, check arguments, clean, what the mismatch says); every file is the export it edits
# but for one property.
CASES = [
    ("film-gds-one-on-layer2.gds", {}, False, "geometry on 2 layers (2/0, 1/0)"),
    ("film-gds-all-on-layer5.gds", {}, False, "geometry on layer 5/0, not 1/0"),
    ("film-gds-datatype3.gds", {}, False, "geometry on layer 1/3, not 1/0"),
    ("film-gds-one-on-layer2-no-sidecar.gds", {}, False, "geometry on 2 layers"),
    ("film-gds-all-on-layer5-no-sidecar.gds", {}, True, "not compared: no export sidecar"),
    ("film-gds-all-on-layer5-no-sidecar.gds", {"vendor": "chrome-photomask"}, False,
     "not 1/0 (export's default layer with the vendor preset chrome-photomask"),
    ("film-gds-sidecar-layer7.gds", {}, False, "geometry on layer 1/0, not 7/0"),
    ("film-gds-sidecar-no-detail.gds", {}, True, "which lists no layer"),
    ("film-oas-all-on-layer5.oas", {}, False, "geometry on layer 5/0, not 1/0"),
    ("film-oas-two-layers-no-sidecar.oas", {}, False, "geometry on 2 layers (1/0, 2/0)"),
    ("film-dxf-renamed-layer.dxf", {}, False, "geometry on layer MASK, not PINMASK"),
    ("film-dxf-renamed-layer-no-sidecar.dxf", {}, True, "MASK, not compared"),
    ("film-dxf-renamed-layer-no-sidecar.dxf", {"vendor": "film-plotter"}, False,
     "not PINMASK"),
    ("film-dxf-one-on-layer-0.dxf", {}, False, "geometry on 2 layers (0, PINMASK)"),
    ("film-gbr-positive.gbr", {}, False, "polarity Positive, not Negative"),
    ("film-gbr-no-polarity.gbr", {}, False, "the file states no polarity"),
    ("film-gbr-dark-negative.gbr", {}, False, "polarity Negative, not Positive"),
    ("film-gbr-positive-no-sidecar.gbr", {}, False, "contradicts the file's own pinmask comment"),
    ("film-gbr-clear-no-sidecar.gbr", {}, True, "Negative, not compared"),
    ("film-gbr-clear-no-sidecar.gbr", {"tone": "dark"}, False, "by the tone given to check"),
]


@pytest.mark.parametrize("name, args, clean, says", CASES)
def test_check_compares_the_film_identity_as_the_command_line(cli, name, args, clean, says,
                                                              monkeypatch):
    monkeypatch.chdir(CORPUS)  # the sidecars give the mask relative to themselves
    path = str(CORPUS / name)
    j = pinmask.check(path, **args)
    assert j["clean"] == clean, j["film_identity"]
    items = j["film_identity"]["items"]
    assert len(items) == 1 and any(says in i["message"] for i in items), items
    assert items[0]["ok"] == clean
    # the same verdict and the same words from `pinmask check --json`
    flags = [x for k, v in args.items() for x in ("--" + k, v)]
    p = cli.run("check", path, "--json", *flags, expect=(0, 1))
    assert p.returncode == (0 if clean else 1)
    assert json.loads(p.stdout)["film_identity"] == j["film_identity"]


def test_what_nothing_says_is_not_known_never_compared():
    j = pinmask.check(str(CORPUS / "film-gds-all-on-layer5-no-sidecar.gds"))
    item = j["film_identity"]["items"][0]
    assert item["expected"] is None and item["found"] == "5/0"
    assert "no vendor preset given" in item["source"]


@pytest.mark.parametrize("name", ["film-gbr-level-clear.gbr", "film-gbr-image-negative.gbr",
                                  "film-gbr-polarity-twice.gbr", "film-gbr-polarity-unknown.gbr"])
def test_polarity_commands_the_writer_never_uses_are_refused(name):
    with pytest.raises(ValueError, match="gerber: at byte"):
        pinmask.check(str(CORPUS / name))
