"""Every command's defaults and refusals: the command line against the module.

Defaults: each flag's default as `pinmask CMD --help` shows it (tests/cli/test_request_defaults.cpp
checks that column against the library requests) against the default of the keyword that flag
spells in the module's functions (python/pinmask.pyi, which tests/python/test_stub_signatures.py
holds to the runtime signatures). A flag's keyword is read from the two spelling tables: the
command line's field -> flag (cli/options/flag_names.cpp) and the module's field -> keyword
(python/keyword_names.cpp; a field without a row is its own keyword).

Refusals: one out-of-range value per setting, given as the flag (exit 2, the flag named, nothing
written) and as the keyword (ValueError naming the keyword, no flag).
"""
import ast
import re

import numpy as np
import pytest

import pinmask
from conftest import SOURCE_DIR
from test_parity_flags import BY_DESIGN, FUNCTIONS, counterpart, lookup

# Keywords whose default is None where the flag shows a value: None is "not given", which leaves
# the library's choice (the value the flag shows), and why the module cannot write that value.
NONE_IS_THE_LIBRARYS = {
    ("generate", "grid"): "paper and mura fix the geometry; a given value is refused",
    ("generate", "holes"): "as grid", ("generate", "tiles"): "as grid",
    ("generate", "spacing"): "as grid",
    ("simulate", "snr_db"): "None with photons= is the photon model",
    ("search", "snr_db"): "as simulate", ("score", "snr_db"): "as simulate",
    ("compare", "snr_db"): "as simulate", ("depth", "snr_db"): "as simulate",
    ("decode", "nsr"): "auto unless given; refused with a method that does not read it",
    ("decode", "lambda_"): "as nsr", ("decode", "regulariser"): "as nsr",
    ("decode", "iters"): "as nsr", ("decode", "tol"): "as nsr",
    ("calibrate", "saturation_level"): "auto: an integer file's largest count (flag only)",
    ("depth", "steps"): "not with distances=", ("depthmap", "steps"): "not with psf_stack=",
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
    function = FUNCTIONS[command][0]  # the command's own function (tests/python/test_parity_flags)
    keywords = stub_defaults()[function]
    compared = 0
    for flag, shown in help_defaults(cli, command).items():
        names = keywords_of(flag) & set(keywords)
        if not names:
            # No keyword by the spelling tables: test_parity_flags says why (by design) or what
            # carries the flag instead (a function, a Camera field), never one of the keywords.
            if lookup(BY_DESIGN, command, flag) is None:
                found = counterpart(command, flag)
                assert found and found not in keywords, f"{command} {flag}: {found}"
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



MASK = SOURCE_DIR / "fuzz" / "corpus" / "mask_json" / "small.mask.json"
CAPTURE = SOURCE_DIR / "fuzz" / "corpus" / "image" / "cap.npy"  # simulated from MASK

DEPTHMAP = "depthmap {capture} --mask {mask} --from 1m --to 2m -o {out}"
SWEEP = dict(from_m=1.0, to_m=2.0)

# One out-of-range value per setting: (command and its other arguments, flag, value, function,
# its other keywords, keyword, value). {mask}, {capture}, {out} are filled in per run.
REFUSALS = [
    ("design", "--lsi-tolerance", "-1", "optics", {}, "lsi_tolerance_px", -1.0),
    ("design", "--grid", "0", "optics", {}, "grid", 0),
    ("design", "--holes", "-1", "optics", {}, "holes", -1),
    ("design", "--tiles", "0", "optics", {}, "tiles", 0),
    ("decode {capture} --mask {mask} -o {out}.tiff --method tv", "--iters", "0", "decode",
     dict(method="tv"), "iters", 0),
    ("decode {capture} --mask {mask} -o {out}.tiff --method tv", "--tol", "-1", "decode",
     dict(method="tv"), "tol", -1.0),
    ("decode {capture} --mask {mask} -o {out}.tiff", "--nsr", "-1", "decode", {}, "nsr", -1.0),
    ("decode {capture} --mask {mask} -o {out}.tiff", "--downsample", "13", "decode", {},
     "downsample", 13),
    ("decode {capture} --mask {mask} -o {out}.tiff", "--threads", "1025", "decode", {},
     "threads", 1025),
    (DEPTHMAP, "--window", "4", "depthmap", SWEEP, "window", 4),
    (DEPTHMAP + " --window 5", "--steps", "1", "depthmap", dict(SWEEP, window=5), "steps", 1),
    (DEPTHMAP + " --window 5", "--smooth", "-1", "depthmap", dict(SWEEP, window=5), "smooth", -1.0),
    (DEPTHMAP + " --window 5", "--nsr", "0", "depthmap", dict(SWEEP, window=5), "nsr", 0.0),
    ("calibrate {capture} --mask {mask} -o {out}", "--max-rotation", "-1", "calibrate", {},
     "max_rotation_deg", -1.0),
    ("calibrate {capture} --mask {mask} -o {out}", "--pitch-range", "0.5", "calibrate", {},
     "pitch_range", 0.5),
    ("calibrate {capture} --mask {mask} -o {out}", "--threshold", "0", "calibrate", {},
     "threshold_sigmas", 0.0),
    ("score {mask}", "--seeds", "0", "score", {}, "noise_seeds", 0),
    ("score {mask}", "--tv-iters", "0", "score", {}, "tv_iterations", 0),
    ("score {mask}", "--nsr", "-1", "score", {}, "nsr", "-1"),
    ("score {mask}", "--prior-scenes", "0", "score", {}, "prior_scenes", 0),
    ("compare {mask}", "--tv-iters", "0", "compare", {}, "tv_iterations", 0),
    ("compare {mask}", "--nsr", "0", "compare", {}, "nsr", "0"),
    ("compare {mask} --baselines", "--baseline-count", "0", "compare", dict(baselines=True),
     "baseline_count", 0),
    ("export {mask} -o {out}", "--layer", "-1", "export_mask", {}, "layer", -1),
    ("export {mask} -o {out}", "--margin", "-1mm", "export_mask", {}, "margin", "-1mm"),
    ("export {mask} -o {out}", "--shape", "hexagon", "export_mask", {}, "shape", "hexagon"),
    ("check {mask}", "--max-xor-um2", "-1", "check", {}, "max_xor_um2", -1.0),
]


def positional(function, tmp_path):
    """The function's leading arguments for MASK and CAPTURE."""
    mask = pinmask.load_mask(MASK)
    capture = np.load(CAPTURE)
    return {"optics": (), "decode": (capture,), "depthmap": (capture,),
            "calibrate": (capture, mask), "score": ([mask],), "compare": ([mask],),
            "export_mask": (mask, str(tmp_path / "py-export")), "check": (mask,)}[function]


@pytest.mark.parametrize("row", REFUSALS, ids=lambda r: f"{r[0].split()[0]}{r[1]}={r[2]}")
def test_the_same_value_is_refused_in_each_face_s_own_words(cli, tmp_path, row):
    command, flag, value, function, others, keyword, py_value = row
    args = command.format(mask=MASK, capture=CAPTURE, out=tmp_path / "out").split()
    message = cli.run(*args, flag, value, expect=2).stderr
    assert flag in message, message
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob("out.*"))
    if function == "decode" or function == "depthmap":
        others = dict(others, mask=pinmask.load_mask(MASK))
    with pytest.raises(ValueError) as e:
        getattr(pinmask, function)(*positional(function, tmp_path), **others,
                                   **{keyword: py_value})
    assert keyword in str(e.value), str(e.value)
    assert "--" not in str(e.value), str(e.value)


def test_threads_zero_is_all_cores_in_both_faces(cli, tmp_path):
    """0 is decode's default thread count (all cores) in the library and the module, so the
    command line takes it as a value too."""
    cli.run("decode", CAPTURE, "--mask", MASK, "--threads", "0", "-o", tmp_path / "d.tiff")
    cli.run("simulate", MASK, "--threads", "0", "-o", tmp_path / "s.tiff")
    mask = pinmask.load_mask(MASK)
    capture = np.load(CAPTURE)
    all_cores = pinmask.decode(capture, mask=mask, threads=0)["image"]
    assert np.array_equal(all_cores, pinmask.decode(capture, mask=mask, threads=1)["image"])
