"""Every command of the executable and every flag of each has a Python counterpart.

The lists come from the executable itself: `pinmask --help` names the commands, `pinmask CMD
--help` each command's flags. A flag's counterpart is, in this order: an entry of BY_DESIGN (no
Python counterpart, and why), an entry of GAPS (not in the module yet: what is missing), a
module function or Camera field named in COUNTERPART, else the keyword its flag spells (`--read-
noise` -> `read_noise`) of one of the command's functions. A flag added to the command line with
none of these fails here; so does a GAPS entry whose keyword the module has gained (remove it).
"""
import re

import pytest

import pinmask

# command -> the module functions that carry it (their keywords are the command's flags).
FUNCTIONS = {
    "design": ["optics", "save_camera", "load_camera"],
    "generate": ["generate"],
    "psf": ["psf", "write_psf"],
    "simulate": ["simulate"],
    "decode": ["decode", "decode_batch"],
    "search": ["search"],
    "score": ["score", "metrics", "analytic_error", "simulated_quality"],
    "calibrate": ["calibrate"],
    "compare": ["compare"],
    "export": ["export_mask"],
    "check": ["check"],
    "depth": ["depth"],
    "sweep": ["sweep"],
    "depthmap": ["depthmap"],
}

# Commands with no function, and why.
COMMANDS_BY_DESIGN = {
    "bench": "benchmarks of the executable against reference code timed in the same run; in "
             "Python, time the functions with timeit",
}

# Commands whose function the module does not have yet.
COMMAND_GAPS = {}

# Flags spelled differently in Python: flag -> keyword, function, or Camera field ("Camera.x").
CAMERA_FIELDS = {
    "--camera": "load_camera",  # camera=pinmask.load_camera(FILE)
    "--preset": "paper_camera",  # camera=pinmask.paper_camera() (the default)
    "--lens-focal": "Camera.lens_focal_m",
    "--sensor-distance": "Camera.sensor_distance_m",
    "--object-distance": "Camera.object_distance_m",
    "--wavelength": "Camera.wavelength_m",
    "--bandwidth": "Camera.bandwidth_m",
    "--pixel-pitch": "Camera.pixel_pitch_m",
    "--pinhole": "Camera.pinhole_m",
    "--sensor": "Camera.sensor_cols",
}
COUNTERPART = {
    "--snr": "snr_db",
    "--tv-iters": "tv_iterations",
    "--energy": "energy_fraction",
    "--lsi-tolerance": "lsi_tolerance_px",
    "--no-nonneg": "nonneg",  # nonneg=False
    "--no-rerank": "rerank_scenes",  # rerank_scenes=[]
    "--no-rerank-tv": "rerank_tv",  # rerank_tv=False
    "--max-rotation": "max_rotation_deg",
    "--threshold": "threshold_sigmas",
    "--saturation": "saturation_level",
    "--lambda": "lambda_",  # lambda is a Python keyword
    ("design", "--save-camera"): "save_camera",
    ("generate", "--output"): "save_mask",
    ("psf", "--output"): "write_psf",  # path=
    ("psf", "--npy"): "npy",
    ("export", "--output"): "out_dir",
    ("export", "--format"): "formats",
    ("export", "--no-psf"): "psf",  # psf=False
    ("decode", "--batch"): "decode_batch",  # decode_batch(captures, **decode keywords)
    ("decode", "--bayer"): "read_image",  # read_image(path, bayer=...) reads camera RAW
    ("calibrate", "--bayer"): "read_image",
    ("depth", "--from"): "from_m",
    ("depth", "--to"): "to_m",
    ("depth", "--no-tv"): "tv",  # tv=False
    ("depthmap", "--from"): "from_m",
    ("depthmap", "--to"): "to_m",
    ("score", "--seeds"): "noise_seeds",
}
# Camera flags name the camera in these commands (elsewhere --object-distance is the refocus
# distance of psf, simulate and decode).
CAMERA_COMMANDS = {"design", "generate", "search", "calibrate"}

ANY = "*"
BY_DESIGN = {
    (ANY, "--help"): "help(pinmask.FUNCTION): the docstring, with units",
    (ANY, "--json"): "every function returns the command's JSON keys as a dict",
    (ANY, "--quiet"): "functions print nothing",
    ("simulate", "--output"): "the capture is returned as an array (write_image writes it)",
    ("simulate", "--explain"): "the returned dict holds the settings the run resolved",
    ("decode", "--output"): "the image is returned as an array (write_image writes it)",
    ("decode", "--bits"): "the image is returned as float64; write_image(path, image, "
                         "scale='max', bits=8) writes decode's PNG",
    ("decode", "--scale"): "the image is returned unscaled; write_image(path, image, scale=) "
                          "applies --scale",
    ("decode", "--stats"): "the stats JSON's values are the returned dict's (channels, window, "
                           "period_check)",
    ("decode", "--batch-format"): "decode_batch returns the images as arrays (write_image "
                                  "writes any of them)",
    ("decode", "--batch-stats"): "decode_batch returns each capture's stats as its dict",
    ("decode", "--explain"): "the returned dict holds what each step decided",
    ("search", "--output"): "the ranked masks are returned as Mask objects under masks "
                            "(Mask.save writes one)",
    ("search", "--explain"): "the returned dict holds the resolved settings and the run's log",
    ("search", "--config"): "a file of flag values: Python passes keywords (search(**settings))",
    ("search", "--migrate-every"): "the MPI island model runs under mpirun, a command-line "
                                   "launch; the module searches in one process",
    ("score", "--explain"): "the returned dict holds the resolved settings",
    ("calibrate", "--output"): "the calibrated PSF, mask and report are returned as values",
    ("depthmap", "--output-dir"): "the maps are returned as arrays beside the summary (write "
                                  "them with write_image)",
    ("sweep", "--output"): "the rows and each point's best mask are returned (Mask.save writes "
                           "one); the sweep's CSV, Markdown table and plots are the command's",
    ("depth", "--output-dir"): "the per-distance figures are returned as dicts (write_image "
                               "writes any image)",
}

# Not in the module yet: (command, flag) -> what is missing.
GAPS = {
}


def commands(exe):
    text = exe.run("--help").stdout
    section = text.split("Subcommands:", 1)[1]
    return re.findall(r"^  ([a-z]+)\s", section, re.M)


def flags(exe, command):
    text = exe.run(command, "--help").stdout
    found = []
    for m in re.finditer(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", text, re.M):
        if m.group(1) not in found:
            found.append(m.group(1))
    return found


def keywords(function):
    """Parameter names from pybind11's signature line (the first docstring line)."""
    first = (function.__doc__ or "").split("\n", 1)[0]
    return set(re.findall(r"(?:\(|, )(\w+): ", first))


def lookup(table, command, flag):
    return table.get((command, flag), table.get((ANY, flag), table.get(flag)))


def counterpart(command, flag):
    """What carries the flag in Python: 'keyword', 'function' or 'Camera.field'; None: nothing."""
    named = lookup(COUNTERPART, command, flag)
    if named is None and command in CAMERA_COMMANDS:
        named = CAMERA_FIELDS.get(flag)
    functions = [getattr(pinmask, f) for f in FUNCTIONS[command] if hasattr(pinmask, f)]
    if named is not None:
        if named.startswith("Camera."):
            if hasattr(pinmask.Camera, named[len("Camera."):]) and any(
                    "camera" in keywords(f) or "mask" in keywords(f) for f in functions):
                return named
            return None
        if hasattr(pinmask, named) and not isinstance(getattr(pinmask, named), type):
            return named  # a function of its own
        return named if any(named in keywords(f) for f in functions) else None
    keyword = flag[2:].replace("-", "_")
    return keyword if any(keyword in keywords(f) for f in functions) else None


def test_every_command_has_a_function(cli):
    listed = commands(cli)
    assert len(listed) >= 13, listed
    for command in listed:
        if command in COMMANDS_BY_DESIGN:
            continue
        assert command in FUNCTIONS, f"pinmask {command} has no Python counterpart"
        present = [f for f in FUNCTIONS[command] if hasattr(pinmask, f)]
        if command in COMMAND_GAPS:
            assert not present, f"pinmask.{present[0]} exists: remove {command} from COMMAND_GAPS"
        else:
            assert present == FUNCTIONS[command], (command, present)


def test_every_flag_has_a_counterpart(cli):
    missing, closed = [], []
    checked = 0
    for command in commands(cli):
        if command in COMMANDS_BY_DESIGN or command in COMMAND_GAPS:
            continue
        for flag in flags(cli, command):
            if lookup(BY_DESIGN, command, flag) is not None:
                continue
            found = counterpart(command, flag)
            if (command, flag) in GAPS:
                if found is not None:
                    closed.append(f"{command} {flag} -> {found}")
                continue
            checked += 1
            if found is None:
                missing.append(f"pinmask {command} {flag}")
    assert not missing, "flags without a Python counterpart (bind them, or list them in " \
                        "BY_DESIGN or GAPS with the reason): " + ", ".join(missing)
    assert not closed, "GAPS entries the module now has: " + ", ".join(closed)
    assert checked > 150


def test_exception_lists_name_real_flags(cli):
    """Every entry names a flag the executable has, and gives a reason."""
    known = {c: set(flags(cli, c)) for c in commands(cli)}
    for table in (BY_DESIGN, GAPS):
        for (command, flag), reason in table.items():
            assert len(reason) > 10, (command, flag)
            if command == ANY:
                assert any(flag in f for f in known.values()), flag
            else:
                assert flag in known[command], (command, flag)
    for key in COUNTERPART:
        if isinstance(key, tuple):
            assert key[1] in known[key[0]], key
        else:
            assert any(key in f for f in known.values()), key
