"""sweep(): `pinmask sweep` with Python's keywords. The same best masks and objectives as the
command's sweep of the same points; the product's order; the command's rules checked before any
search starts."""
import json

import pytest

import pinmask

BASE = dict(grid=8, evals=300, rerank_scenes=[], tiles=2)


def test_sweep_equals_the_command(cli, tmp_path):
    (tmp_path / "sw.json").write_text(json.dumps({
        "format": "pinmask-sweep", "version": 1,
        "base": {"grid": 8, "evaluations_per_chain": 300, "rerank_scenes": [], "tiles": 2},
        "grid": {"seed": [1, 2], "holes": [5, 8]}}))
    c = json.loads(cli.run("sweep", "sw.json", "-o", "out", "--json", "--quiet").stdout)
    p = pinmask.sweep(product={"seed": [1, 2], "holes": [5, 8]}, **BASE)
    assert p["keys"] == c["keys"] == ["holes", "seed"]
    assert p["points"] == c["points"] == 4
    # keys in alphabetical order, the last varying fastest
    assert [(r["holes"], r["seed"]) for r in p["rows"]] == [(5, 1), (5, 2), (8, 1), (8, 2)]
    for a, b in zip(p["rows"], c["rows"]):
        assert set(a) == set(b)
        assert str(a["holes"]) == b["holes"] and str(a["seed"]) == b["seed"]
        for k in set(a) - {"holes", "seed"}:
            assert a[k] == b[k], k
    for mask, row in zip(p["masks"], p["rows"]):
        assert mask.geometry_hash() == row["geometry_hash"]
        assert len(mask.pattern.pinholes) == row["holes"]


def test_sweep_points_and_progress():
    seen = []
    r = pinmask.sweep(points=[{"holes": 4}, {"holes": 6, "seed": 3}, {"holes": 7}],
                      progress=lambda info: seen.append(info["done"]) or info["done"] < 2,
                      **BASE)
    assert seen == [1, 2] and r["points"] == 2  # False after the second point stops the sweep
    assert r["keys"] == ["holes", "seed"]
    assert r["rows"][0]["seed"] is None  # not set there: search()'s default
    one = pinmask.search(holes=6, seed=3, threads=1, **BASE)
    assert r["rows"][1]["geometry_hash"] == one["masks"][0].geometry_hash()
    assert r["rows"][1]["geometry_hash"] == one["ranked"][0]["geometry_hash"]
    assert r["rows"][1]["objective"] == pytest.approx(one["ranked"][0]["objective"], rel=1e-12)


@pytest.mark.parametrize("kw, fragment", [
    (dict(product={"holes": [4]}, grid=8), "point 0 evals = unset: every point needs"),
    (dict(product={"holes": [4]}, grid=8, evals=100, threads=0), "threads = 0"),
    (dict(product={"nope": [1]}, **BASE), "product key = nope: is not a keyword of search()"),
    (dict(product={"holes": []}, **BASE), "product.holes = []"),
    (dict(product={"holes": "45"}, **BASE), "product.holes"),
    (dict(points=[], **BASE), "points = []"),
    (dict(**BASE), "exactly one of product and points"),
    (dict(product={"holes": [4]}, points=[{"holes": 4}], **BASE), "exactly one of"),
    (dict(product={"holes": list(range(101)), "seed": list(range(100))}, **BASE), "at most 10000"),
    (dict(points=[{"holes": 4}, {"holes": 99}], **BASE), "sweep point 1 (holes = 99): "),
])
def test_sweep_refusals(kw, fragment):
    with pytest.raises(ValueError) as e:
        pinmask.sweep(**kw)
    assert fragment in str(e.value)
