"""Builds the Python module pinmask with CMake for pip and python3 -m build (pyproject.toml).

Only the target pinmask_python is built (the libraries it links, never the command line, tests or
benchmarks), in build-pip/ beside this file (or $PINMASK_PIP_BUILD_DIR), Release, with Ninja when
it is on PATH. The folder CMake makes, pinmask/ (the extension as the package's __init__, the stub
__init__.pyi and py.typed; python/CMakeLists.txt), is what the wheel holds.

Compiler cache: with ccache on PATH the compiler runs through it and CCACHE_BASEDIR defaults to
this folder, so the objects of an earlier build of the same sources (build/, another checkout)
are reused: ccache writes paths under the base folder relative to the build folder, the same for
build/ and build-pip/. $CMAKE_ARGS adds configure arguments (e.g. a launcher of your own).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project() (the module's __version__ is the same)."""
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(pinmask VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("PINMASK_PIP_BUILD_DIR", SOURCE / "build-pip"))
        env = dict(os.environ)
        extra = shlex.split(env.get("CMAKE_ARGS", ""))
        args = ["-DCMAKE_BUILD_TYPE=Release", f"-DPYTHON_EXECUTABLE={sys.executable}",
                f"-DPython_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            args += ["-G", "Ninja"]
        if shutil.which("ccache") and not any("COMPILER_LAUNCHER" in a for a in extra):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            env.setdefault("CCACHE_BASEDIR", str(SOURCE))
            # Precompiled headers are cached only with these (ccache's documentation).
            env.setdefault("CCACHE_SLOPPINESS", "pch_defines,time_macros,include_file_mtime,"
                                                "include_file_ctime")
        jobs = env.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "-S", str(SOURCE), "-B", str(build_dir), *args, *extra],
                       check=True, env=env)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "pinmask_python", "-j",
                        jobs], check=True, env=env)
        package = build_dir / "python" / "pinmask"
        built = Path(self.get_ext_fullpath(ext.name))  # <build_lib>/pinmask/__init__.<suffix>
        built.parent.mkdir(parents=True, exist_ok=True)
        for f in package.iterdir():
            if f.name.startswith("__init__.") and f.suffix == ".so":
                shutil.copyfile(f, built)
            elif f.name in ("__init__.pyi", "py.typed"):
                shutil.copyfile(f, built.parent / f.name)


# setuptools' own folders in build-pip/ too (its default, build/, is the CMake build folder).
setup(version=project_version(),
      options={"build": {"build_base": str(Path("build-pip") / "setuptools")}},
      ext_modules=[Extension("pinmask.__init__", sources=[])],
      cmdclass={"build_ext": CMakeBuild})
