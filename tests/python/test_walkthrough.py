"""examples/python/walkthrough.py runs, and every figure it makes equals the command line's for
the same inputs: the optics, the searched mask, the fabrication files, the simulated capture and
its decode, the refocused capture and decode, the calibration and the loss against distance."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest


def same_image(py_array, cli_file):
    """The CLI writes .npy in its own dtype (float32 for images): compare at that precision."""
    ref = np.load(cli_file)
    assert py_array.shape == ref.shape, (py_array.shape, ref.shape)
    assert np.array_equal(py_array.astype(ref.dtype), ref), cli_file


def test_walkthrough_figures_equal_the_cli(cli, tmp_path, source_dir):
    out = tmp_path / "out"
    env = dict(os.environ, PINMASK_WISDOM="off")
    p = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / "walkthrough.py"),
                        str(out)], capture_output=True, text=True, timeout=600, env=env)
    assert p.returncode == 0, p.stderr
    summary = json.loads((out / "walkthrough.json").read_text())
    for png in ["psf", "capture", "decoded", "refocus-capture", "refocused"]:
        assert (out / f"{png}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

    design = json.loads(cli.run("design", "--camera", out / "nir.camera.json", "--grid", "8",
                                "--holes", "6", "--json").stdout)
    assert design["pixels_per_cell"] == summary["pixels_per_cell"]

    cli.run("search", "--camera", out / "nir.camera.json", "--grid", "8", "--holes", "6..10",
            "--evals", "300", "--threads", "1", "--seed", "3", "--top", "1", "--no-rerank",
            "-o", "runs")
    assert (tmp_path / "runs" / "rank-1.mask.json").read_text() == \
        (out / "best.mask.json").read_text()
    mask = out / "best.mask.json"

    cli.run("export", mask, "--format", "svg,gds", "--no-psf", "-o", "fab")
    for name in summary["export_files"]:
        assert (tmp_path / "fab" / name).read_bytes() == (out / "fab" / name).read_bytes(), name

    cli.run("simulate", mask, "--scene", "letter-R", "--snr", "40", "--seed", "1", "-o",
            "capture.npy")
    same_image(np.load(out / "capture.npy"), tmp_path / "capture.npy")
    cli.run("decode", out / "capture.npy", "--mask", mask, "--method", "wiener", "--nsr", "1e-3",
            "-o", "decoded.npy")
    same_image(np.load(out / "decoded.npy"), tmp_path / "decoded.npy")

    cli.run("simulate", mask, "--scene", "letter-R", "--snr", "40", "--seed", "1", "--geometry",
            "exact", "--object-distance", "2m", "--size", "240x320", "-o", "far.npy")
    same_image(np.load(out / "refocus-capture.npy"), tmp_path / "far.npy")
    cli.run("decode", out / "refocus-capture.npy", "--mask", mask, "--object-distance", "2m",
            "--nsr", "1e-3", "--stats", "refocus.json", "-o", "refocused.npy")
    same_image(np.load(out / "refocused.npy"), tmp_path / "refocused.npy")
    stats = json.loads((tmp_path / "refocus.json").read_text())
    assert stats["psf"]["refocus"] == summary["refocus"]

    cal = json.loads(cli.run("calibrate", out / "point.npy", "--mask", mask, "-o", "cal",
                             "--json").stdout)
    assert cal["rotation_deg"] == summary["calibrate"]["rotation_deg"]
    assert list(cal["pitch_px"]) == summary["calibrate"]["pitch_px"]

    depth = json.loads(cli.run("depth", mask, "--from", "0.9m", "--to", "2m", "--steps", "4",
                               "--photons", "200", "--read-noise", "6", "--no-tv",
                               "--json").stdout)
    # The same library call: equal to the JSON's 17 significant digits.
    assert [r["wiener_psnr_loss_db"] for r in depth] == \
        pytest.approx([r["wiener_psnr_loss_db"] for r in summary["depth"]], rel=1e-12)
