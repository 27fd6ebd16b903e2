"""search() checkpoints: the command's file format and configuration. A checkpoint the command
wrote resumes in Python to the uninterrupted run's masks, and a Python checkpoint resumes in the
command; another configuration is refused naming the keys; the command's rules, in keywords."""
import json

import pytest

import pinmask

# Anneal restarts every 20000 moves: 70000 evaluations a chain pass three checkpoint boundaries.
KW = dict(grid=12, holes=8, pixels_per_cell=4, tiles=1, prior_scenes=2, threads=1, top=3, seed=2,
          rerank_scenes=["letter-R"], rerank_tv=False, evals=70000)
FLAGS = ["--grid", "12", "--holes", "8", "--pixels-per-cell", "4", "--tiles", "1",
         "--prior-scenes", "2", "--threads", "1", "--top", "3", "--seed", "2", "--rerank-scenes",
         "letter-R", "--no-rerank-tv", "--quiet", "--evals", "70000"]


def hashes(result):
    return [m.geometry_hash() for m in result["masks"]]


def test_checkpoints_cross_the_faces(cli, tmp_path):
    full = pinmask.search(**KW)
    # The command's checkpoint (its last boundary) resumed by search().
    cli.run("search", *FLAGS, "--checkpoint", "ck.json", "--checkpoint-every", "20000", "-o", "a")
    assert json.loads((tmp_path / "ck.json").read_text())["segment"] == 3
    # (the same settings: checkpoint_every is one of them, as for the command)
    resumed = pinmask.search(**KW, resume=str(tmp_path / "ck.json"),
                             checkpoint=str(tmp_path / "r.json"), checkpoint_every=20000)
    assert hashes(resumed) == hashes(full)
    assert [c["objective"] for c in resumed["ranked"]] == [c["objective"] for c in full["ranked"]]
    # search()'s checkpoint: the command's bytes, and the command resumes it.
    py = pinmask.search(**KW, checkpoint=str(tmp_path / "py.json"), checkpoint_every=20000)
    assert hashes(py) == hashes(full)
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "ck.json").read_bytes()
    ranked = json.loads(cli.run("search", *FLAGS, "--checkpoint", "py2.json",
                                "--checkpoint-every", "20000", "--resume", "py.json", "-o", "b",
                                "--json").stdout)["ranked"]
    assert [pinmask.load_mask(str(tmp_path / r["path"])).geometry_hash()
            for r in ranked] == hashes(full)


def test_resume_of_another_configuration_is_refused(tmp_path):
    pinmask.search(**KW, checkpoint=str(tmp_path / "ck.json"), checkpoint_every=20000)
    other = dict(KW, seed=3)
    with pytest.raises(ValueError) as e:
        pinmask.search(**other, resume=str(tmp_path / "ck.json"))
    assert "differing keys: checkpoint_every, seed" in str(e.value)


@pytest.mark.parametrize("kw, fragment", [
    (dict(checkpoint_every=100), "checkpoint_every: needs checkpoint FILE"),
    (dict(checkpoint="CK"), "checkpoint: needs checkpoint_every"),
    (dict(checkpoint="/nonexistent/ck.json", checkpoint_every=100), "its folder does not exist"),
    (dict(checkpoint="CK", checkpoint_every=100, evals=0), "needs an evaluation budget (evals)"),
    (dict(resume="/nonexistent/ck.json"), "resume"),
])
def test_checkpoint_refusals(tmp_path, kw, fragment):
    kw = {k: (str(tmp_path / "ck.json") if v == "CK" else v) for k, v in kw.items()}
    with pytest.raises(ValueError) as e:
        pinmask.search(**dict(KW, **kw))
    assert fragment in str(e.value) and "--" not in str(e.value)
