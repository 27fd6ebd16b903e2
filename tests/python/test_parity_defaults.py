"""Every command's defaults and refusals: the command line against the module.

Defaults: each flag's default as `pinmask CMD --help` shows it (tests/cli/test_request_defaults.cpp
checks that column against the library requests) against the default of the keyword that flag
spells in the module's functions (python/pinmask.pyi, which tests/python/test_stub_signatures.py
holds to the runtime signatures). A flag's keyword is read from the two spelling tables: the
command line's field -> flag (cli/options/flag_names.cpp) and the module's field -> keyword
(python/keyword_names.cpp; a field without a row is its own keyword).

Refusals: one out-of-range value per setting, given as the flag (exit 2, the flag named) and as the
keyword (ValueError naming the keyword).
"""
import ast
import re

import numpy as np
import pytest

import pinmask
from conftest import SOURCE_DIR

# command -> the module function that carries it.
FUNCTIONS = {"design": "optics", "generate": "generate", "psf": "psf", "simulate": "simulate",
             "decode": "decode", "search": "search", "score": "score", "calibrate": "calibrate",
             "compare": "compare", "export": "export_mask", "check": "check", "depth": "depth",
             "sweep": "sweep", "depthmap": "depthmap"}

# Keywords whose default is None where the flag shows a value: None is "not given", which leaves
# the library's choice (the value the flag shows), and why the module cannot write that value.
NONE_IS_THE_LIBRARYS = {
    ("generate", "grid"): "paper and mura fix the geometry; a given value is refused",
    ("generate", "holes"): "as grid", ("generate", "tiles"): "as grid",
    ("generate", "spacing"): "as grid",
    ("simulate", "snr_db"): "None with photons= is the photon model", ("search", "snr_db"): "",
    ("score", "snr_db"): "", ("compare", "snr_db"): "", ("depth", "snr_db"): "",
    ("decode", "nsr"): "auto unless given; refused with a method that does not read it",
    ("decode", "lambda_"): "as nsr", ("decode", "regulariser"): "as nsr",
    ("decode", "iters"): "as nsr", ("decode", "tol"): "as nsr",
    ("calibrate", "saturation_level"): "auto: an integer file's largest count (flag only)",
    ("depth", "steps"): "not with distances=", ("depthmap", "steps"): "not with psf_stack=",
}
# Flags with a default and no keyword, and why.
NO_KEYWORD = {
    "--preset": "camera=pinmask.paper_camera() is the default camera",
    "--bits": "decode: the PNG file's bit depth (the module returns arrays)",
    "--scale": "decode: the PNG file's scaling", "--batch-format": "decode: the files of --batch",
    "--bayer": "camera RAW files: read_image(bayer=) reads them for the module",
    "--output-dir": "depthmap writes files only when output_dir= is given",
    "--migrate-every": "search: ranks under mpirun",
}


def table(path):
    return re.findall(r'\{"([^"]+)", "([^"]+)"\}', (SOURCE_DIR / path).read_text())


FLAG_ROWS = table("cli/options/flag_names.cpp")
KEYWORD_OF_FIELD = dict(table("python/keyword_names.cpp"))


def keywords_of(flag):
    return {KEYWORD_OF_FIELD.get(field, field) for field, f in FLAG_ROWS if f == flag}


def stub_defaults():
    """function -> {keyword: default}, the defaults as Python values."""
    out = {}
    for node in ast.parse((SOURCE_DIR / "python" / "pinmask.pyi").read_text()).body:
        if isinstance(node, ast.FunctionDef):
            a = node.args
            pairs = list(zip(a.args[len(a.args) - len(a.defaults):], a.defaults))
            pairs += [(p, d) for p, d in zip(a.kwonlyargs, a.kw_defaults) if d is not None]
            out[node.name] = {p.arg: ast.literal_eval(d) for p, d in pairs}
    return out


def help_defaults(cli, command):
    """flag -> the default `pinmask COMMAND --help` shows (CLI11's `--flag TYPE=VALUE`)."""
    out = {}
    for line in cli.run(command, "--help").stdout.splitlines():
        if not line.startswith("  -"):
            continue
        column = re.split(r"\s{2,}", line.strip())[0]
        names, _, rest = column.partition(" ")
        m = re.match(r"\S+?=(\S+)", rest)
        for name in names.split(","):
            if name.startswith("--") and m:
                out[name] = m.group(1)
    return out


def same(shown, default):
    if isinstance(default, bool):
        return shown == str(default).lower()
    if isinstance(default, (int, float)):
        return float(shown) == default
    if isinstance(default, (tuple, list)):
        return shown.strip("[]") == ",".join(default)
    return shown == default


@pytest.mark.parametrize("command", sorted(FUNCTIONS))
def test_every_flag_default_is_the_keyword_default(cli, command):
    function = FUNCTIONS[command]
    keywords = stub_defaults()[function]
    compared = 0
    for flag, shown in help_defaults(cli, command).items():
        names = keywords_of(flag) & set(keywords)
        if not names:
            assert flag in NO_KEYWORD, f"{command} {flag}={shown}: no keyword of {function}()"
            continue
        for name in names:
            default = keywords[name]
            if default is None:
                assert (command, name) in NONE_IS_THE_LIBRARYS, (command, flag, shown, name)
                continue
            assert same(shown, default), f"{command} {flag}={shown} but {function}({name}=" \
                                         f"{default!r})"
            compared += 1
    if command != "sweep":  # sweep's flags (a config file, an output folder) have no defaults
        assert compared >= 1, command

