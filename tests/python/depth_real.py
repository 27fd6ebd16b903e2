"""The real tilted USAF target of DiffuserCam 3D (PINMASK_SHARED_DIR/data/real/
waller-lab-diffusercam-3d, its README) under the depth costs of depth_costs.py: the raw capture
minus its camera bias of 100 counts, each measured PSF minus its median (the stack's floor),
clipped at 0; the 44 planes in the stack's order (it gives no distances)."""
import os
import pathlib

import numpy as np
from scipy.stats import spearmanr

import depth_costs as dc
import pinmask

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
# The target's patch (rows, cols) where a single-plane decode shows the bars (the README).
TARGET = (slice(80, 190), slice(100, 230))


def folder():
    shared = pathlib.Path(os.environ.get("PINMASK_SHARED_DIR", SOURCE_DIR.parent / "shared"))
    return shared / "data" / "real" / "waller-lab-diffusercam-3d"


def load(path):
    raw = np.asarray(pinmask.read_image(str(path / "example_raw.png"))[0], float).squeeze()
    psfs = []
    for k in range(44):
        p = np.asarray(pinmask.read_image(str(path / "psf_stack" / f"psf{k:02d}.tiff"))[0],
                       float).squeeze()
        psfs.append(np.maximum(p - np.median(p), 0.0))
    return np.maximum(raw - 100.0, 0.0), psfs


def figures(raw, psfs, kind, window=61):
    """The plane of the lowest frame-mean cost, and the Spearman correlation of the per-pixel
    plane (lowest cost) with the column and with the row over the target's patch."""
    c = dc.costs(raw / raw.max(), psfs, kind, window)
    label = c.argmin(0)[TARGET]
    rows, cols = np.mgrid[TARGET]
    return (int(c.mean((1, 2)).argmin()), float(spearmanr(label.ravel(), cols.ravel())[0]),
            float(spearmanr(label.ravel(), rows.ravel())[0]))


def depthmap_figures(raw, psfs, window=121):
    """pinmask.depthmap over the stack (plane k at a nominal 1/u = 1 + k per metre, monotonic as
    the stack's order), default smoothing: the whole-capture plane, the median plane over the
    target's patch, the Spearman correlations of the refined plane with column and row, and the
    whole-capture plane by the evidence."""
    stack = [(1.0 / (1.0 + k), p) for k, p in enumerate(psfs)]
    r = pinmask.depthmap(raw / raw.max(), psf_stack=stack, window=window)
    plane = (1.0 / r["depth_m"] - 1.0)[TARGET]
    rows, cols = np.mgrid[TARGET]
    return (float(1.0 / r["capture_depth_m"] - 1.0), float(np.median(plane)),
            float(spearmanr(plane.ravel(), cols.ravel())[0]),
            float(spearmanr(plane.ravel(), rows.ravel())[0]),
            float(1.0 / r["capture_evidence_depth_m"] - 1.0))
