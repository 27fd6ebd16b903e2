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


def test_fft_planning_is_announced_once_per_size(cli):
    """With a wisdom file, the first run measures its plans and says so once per size; the next
    run finds them in the file and says nothing (core/fft/planning_notice.hpp)."""
    rng = np.random.default_rng(4)
    np.save(cli.cwd / "small.npy", rng.random((48, 40)))
    psf = np.zeros((48, 40))
    psf[0, 0] = psf[5, 7] = 1.0
    np.save(cli.cwd / "small_psf.npy", psf)
    env = dict(os.environ, PINMASK_WISDOM=str(cli.cwd / "wisdom"))

    def run(out):
        p = subprocess.run([cli.exe, "decode", "small.npy", "--psf", "small_psf.npy",
                            "--crop", "none", "--model", "cyclic", "-o", out], cwd=cli.cwd,
                           env=env,
                           capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
        return [l for l in p.stderr.splitlines() if "planning FFTs" in l]

    first = run("a.npy")
    assert len(first) == 1, first
    assert "48 x 40" in first[0] and "kept in" in first[0], first
    assert run("b.npy") == []
