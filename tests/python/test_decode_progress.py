"""`pinmask decode` reports a long iterative decode on stderr, as plain lines when stderr is a
pipe, and says nothing under --quiet. The decodes run with --tol 0 and far more iterations than
they need, and are stopped by SIGINT once seen (the estimate so far is written, exit 0), so no
test depends on how fast the machine is."""
import os
import signal
import subprocess
import time

import numpy as np

PROGRESS = "pinmask decode: "


def long_decode(cli, *extra):
    rng = np.random.default_rng(3)
    np.save(cli.cwd / "cap.npy", rng.random((512, 512)))
    psf = np.zeros((48, 48))
    psf[::6, ::6] = 1.0
    np.save(cli.cwd / "psf.npy", psf)
    env = dict(os.environ, PINMASK_WISDOM="off")
    return subprocess.Popen(
        [cli.exe, "decode", "cap.npy", "--psf", "psf.npy", "--method", "tv", "--model", "linear",
         "--crop", "none", "--iters", "1000000", "--tol", "0", "-o", "out.npy", *extra],
        cwd=cli.cwd, stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)


def test_progress_lines_reach_a_pipe(cli):
    p = long_decode(cli)
    seen = []
    try:
        for line in p.stderr:  # a pipe: plain lines, the first after 2 s
            if line.startswith(PROGRESS) and "iteration" in line:
                seen.append(line)
                break
    finally:
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=300)
    assert seen, err
    assert "of at most 1000000" in seen[0] and "s left" in seen[0], seen
    assert p.returncode == 0, err
    assert (cli.cwd / "out.npy").exists()
    assert "\r" not in err  # no terminal bar on a pipe


def test_quiet_says_nothing(cli):
    p = long_decode(cli, "--quiet")
    time.sleep(3.5)  # past the 2 s after which a decode without --quiet reports
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=300)
    assert p.returncode == 0, err
    assert not [l for l in err.splitlines() if l.startswith(PROGRESS)], err
