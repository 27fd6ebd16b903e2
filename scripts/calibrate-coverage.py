#!/usr/bin/env python3
"""Measures the coverage of calibrate's 1-sigma intervals (docs/calibration.md, Uncertainties):
each setup of tests/python/test_calibrate_coverage.py rendered once by the numpy model of
tests/python/calib_render.py, then calibrated for each noise seed.
Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/calibrate-coverage.py [SEEDS [SETUP...]]
(default 50 seeds; setups phone-full phone-crop-1024 nir-crop-512). Prints one table row per
setup and parameter: the share of seeds whose interval holds the truth, the mean error and the
errors' spread, both in units of the rms stated sigma."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "python"))
from test_calibrate_coverage import coverage  # noqa: E402

seeds = int(sys.argv[1]) if len(sys.argv) > 1 else 50
setups = sys.argv[2:] or ["phone-full", "phone-crop-1024", "nir-crop-512"]
print("| setup | parameter | covered (1 sigma) | mean error / sigma | spread / sigma |")
print("|---|---|---|---|---|")
for name in setups:
    for p, (c, bias, spread) in coverage(name, range(1, seeds + 1)).items():
        print(f"| {name} | {p} | {100 * c:.0f} % | {bias:+.2f} | {spread:.2f} |", flush=True)
