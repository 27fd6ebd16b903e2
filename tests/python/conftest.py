"""Shared fixtures of the pytest suite of the pinmask Python module.

Run by CTest (tests/CMakeLists.txt) as `/usr/bin/python3 -m pytest tests/python` with
PYTHONPATH = the build's python/ folder and PINMASK_EXE = the pinmask executable, so the module
and the command line of the same build are compared.
"""
import os
import pathlib
import subprocess

import pytest

# FFTW_ESTIMATE plans, no wisdom file, for the module (read at import, core/fft/fft_environment) and
# for every command the suite runs: the same plans, so the same rounding, whatever the user's
# wisdom cache holds.
os.environ["PINMASK_WISDOM"] = "off"

import pinmask  # noqa: E402 (after the environment it reads at import)

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]


def _exe():
    exe = os.environ.get("PINMASK_EXE")
    if exe:
        return exe
    guess = SOURCE_DIR / "build" / "cli" / "pinmask"
    return str(guess)


class Cli:
    """Runs the pinmask executable of the same build."""

    def __init__(self, exe, cwd):
        self.exe = exe
        self.cwd = cwd

    def run(self, *args, expect=0):
        # FFTW_ESTIMATE plans (no wisdom file), as the module plans (above): the same rounding.
        env = dict(os.environ, PINMASK_WISDOM="off")
        p = subprocess.run([self.exe, *map(str, args)], cwd=self.cwd, capture_output=True,
                           text=True, timeout=300, env=env)
        allowed = expect if isinstance(expect, tuple) else (expect,)
        assert p.returncode in allowed, (args, p.returncode, p.stdout, p.stderr)
        return p

    def error(self, *args):
        """The message of a run that must fail with exit code 2 ('pinmask: error: ' removed)."""
        p = self.run(*args, expect=2)
        lines = [l for l in p.stderr.splitlines() if l.startswith("pinmask: error: ")]
        assert lines, p.stderr
        return lines[-1][len("pinmask: error: "):]


@pytest.fixture
def cli(tmp_path):
    exe = _exe()
    if not os.path.exists(exe):
        pytest.fail(f"pinmask executable not found at {exe} (set PINMASK_EXE)")
    return Cli(exe, tmp_path)


@pytest.fixture
def mask7():
    """The README tour's mask: random, 16 x 16, K = 20, spacing 2, 2 x 2 tiles, seed 7."""
    return pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=7)


@pytest.fixture
def bad_inputs():
    return SOURCE_DIR / "tests" / "bad-inputs"


@pytest.fixture
def source_dir():
    return SOURCE_DIR
