"""Search: the module against `pinmask search` (the same pipeline), progress and Ctrl-C."""
import os
import signal
import threading
import time

import pytest

import pinmask


def test_search_same_masks_as_cli(cli, tmp_path):
    cli.run("search", "--preset", "paper", "--grid", "16", "--holes", "20", "--evals", "400",
            "--threads", "1", "--seed", "5", "--top", "3", "--no-rerank", "-o", "runs")
    r = pinmask.search(grid=16, holes=20, evals=400, threads=1, seed=5, top=3, rerank_scenes=[])
    assert r["stop_reason"] == "evaluation budget" and r["evaluations"] == 400
    assert r["reranked"] == 0
    assert len(r["ranked"]) == len(r["masks"]) == 3
    for i, m in enumerate(r["masks"]):
        assert m.to_json() == (tmp_path / "runs" / f"rank-{i + 1}.mask.json").read_text()
    objectives = [c["objective"] for c in r["ranked"]]
    assert objectives == sorted(objectives)
    # The bound on any 20-pinhole pattern is above every candidate's analytic PSNR.
    for c in r["ranked"]:
        assert c["upper_bound_analytic_mmse_psnr_db"] >= c["analytic_mmse_psnr_db"]


@pytest.mark.parametrize("noise, figure", [(dict(snr_db=30), "analytic_mmse_psnr_db"),
                                           (dict(photons=5), "analytic_wiener_psnr_db")])
def test_search_figure_is_compares_lead_figure(noise, figure):
    # The figure the search optimised has one name in its result, its masks and compare, and
    # compare computes the same value for the same mask, prior and noise.
    r = pinmask.search(grid=8, holes=5, tiles=1, pixels_per_cell=4, evals=200, seed=2, top=1,
                       prior_scenes=2, rerank_scenes=[], **noise)
    assert r["objective_figure"] == figure
    c, mask = r["ranked"][0], r["masks"][0]
    assert mask.objective_figure == figure
    assert '"objective_figure": "%s"' % figure in mask.to_json()
    out = pinmask.compare([mask], prior_scenes=2, scenes=["letter-R"], tv_iterations=5,
                          **noise)
    assert out["lead_figure"]["name"] == figure
    assert abs(out["masks"][0][figure] - c[figure]) <= 1e-9
    assert abs(out["masks"][0]["analytic_mmse_psnr_db"] - c["analytic_mmse_psnr_db"]) \
        <= 1e-9


def test_search_keep_out_and_rerank_same_masks_as_cli(cli, tmp_path):
    cli.run("search", "--preset", "paper", "--grid", "16", "--holes", "20", "--evals", "200",
            "--threads", "1", "--seed", "6", "--top", "2", "--keep-out", "border",
            "--rerank-scenes", "letter-R", "--no-rerank-tv", "-o", "runs")
    r = pinmask.search(grid=16, holes=20, evals=200, threads=1, seed=6, top=2,
                       keep_out="border", rerank_scenes=["letter-R"], rerank_tv=False)
    assert r["reranked"] == 2 and len(r["ranked"]) == 2
    for i, (c, m) in enumerate(zip(r["ranked"], r["masks"])):
        assert c["reranked"] and c["sim_wiener_psnr_db"] > 0
        assert m.to_json() == (tmp_path / "runs" / f"rank-{i + 1}.mask.json").read_text()
        # keep-out border: no pinhole on the outer ring of the grid
        for (row, col) in m.pattern.pinholes:
            assert 0 < row < 15 and 0 < col < 15
    psnrs = [c["sim_wiener_psnr_db"] for c in r["ranked"]]
    assert psnrs == sorted(psnrs, reverse=True)  # re-ranked: best simulated PSNR first


def test_search_progress_and_stop():
    rows = []

    def progress(row):
        rows.append(row)
        return len(rows) < 3  # stop at the third report

    r = pinmask.search(grid=16, holes=20, time="60s", threads=1, seed=2, top=2,
                       progress=progress, strategy="random", rerank_scenes=[])
    assert len(rows) == 3 and r["stop_reason"] == "interrupted"
    assert all(row["phase"] == "search" and 0 <= row["fraction"] <= 1 for row in rows)
    assert r["ranked"] and r["masks"] and r["used_s"] < 30


def test_search_ctrl_c_raises_keyboard_interrupt():
    """Ctrl-C one second into a 30 s search is Python's KeyboardInterrupt, raised at once (a
    progress callback returning False is the way to stop and keep the best so far)."""
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.0, interrupt)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            pinmask.search(grid=16, holes=20, time="30s", threads=1, seed=3, top=2)
    finally:
        timer.cancel()
    ended = time.monotonic()
    # It stopped at the signal, not at the end of its budget (the latency is in docs/python.md).
    assert sent and ended - start < 30


def test_search_bad_input_same_message_as_cli(cli):
    msg = cli.error("search", "--grid", "16", "--holes", "200", "--evals", "10", "--threads", "1",
                    "-o", "runs")
    with pytest.raises(ValueError) as e:
        pinmask.search(grid=16, holes=200, evals=10)
    # The same words, the setting spelled as the keyword instead of the flag.
    assert msg.startswith("--holes = 200: ")
    assert str(e.value) == msg.replace("--holes", "holes")
    with pytest.raises(ValueError, match="^filter = nsr:-1"):
        pinmask.search(evals=10, filter="nsr:-1")
