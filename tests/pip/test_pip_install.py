"""Installable the Python way: `pip install --no-build-isolation .` (pyproject.toml, setup.py) in
a fresh virtual environment that sees Debian's packages (--system-site-packages: numpy,
setuptools), then the installed module, not the build tree's, runs a search whose best mask is
the command line's, byte for byte.

The checkout is copied first (without build folders), so the test writes nothing into the source
tree. setup.py compiles through ccache with the copy as CCACHE_BASEDIR, so the objects of the
build this test belongs to (scripts/build: ccache, the checkout as base folder) are reused.
"""
import os
import pathlib
import shutil
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[2]

SEARCH_SCRIPT = """
import sys
import pinmask
r = pinmask.search(grid=16, holes=20, evals=150, threads=1, seed=4, top=1, rerank_scenes=[])
print(pinmask.__file__)
sys.stdout.write(r["masks"][0].to_json())
"""


def ignore(folder, names):
    """Build folders and caches at the top, caches anywhere."""
    skip = {n for n in names if n in ("__pycache__", ".git") or n.endswith(".egg-info")}
    if pathlib.Path(folder) == SOURCE:
        skip |= {n for n in names if n.startswith("build")}
    return skip


def run(args, **kw):
    p = subprocess.run([str(a) for a in args], capture_output=True, text=True, **kw)
    assert p.returncode == 0, (args, p.stdout[-4000:], p.stderr[-4000:])
    return p


def test_pip_install_in_a_fresh_venv_gives_the_cli_search(tmp_path):
    src = tmp_path / "src"
    shutil.copytree(SOURCE, src, ignore=ignore)
    venv = tmp_path / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", venv])
    py = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    # --no-index: nothing is downloaded (numpy and setuptools come from the system packages).
    run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index", "."], cwd=src, env=env)
    shutil.rmtree(src / "build-pip")  # the objects (ccache keeps them)

    work = tmp_path / "work"
    work.mkdir()
    env["PINMASK_WISDOM"] = "off"
    out = run([py, "-c", SEARCH_SCRIPT], cwd=work, env=env).stdout
    module_file, mask_json = out.split("\n", 1)
    package = pathlib.Path(module_file).parent
    assert package.parent.name == "site-packages" and venv in package.parents, module_file
    assert (package / "py.typed").exists()
    assert (package / "__init__.pyi").read_text() == (SOURCE / "python" / "pinmask.pyi").read_text()

    run([os.environ["PINMASK_EXE"], "search", "--preset", "paper", "--grid", "16", "--holes", "20",
         "--evals", "150", "--threads", "1", "--seed", "4", "--top", "1", "--no-rerank", "-o",
         "runs"], cwd=work, env=env)
    assert mask_json == (work / "runs" / "rank-1.mask.json").read_text()
