"""The default sweep of `pinmask depthmap` for the four cameras of docs/depth.md section 3a (their
masks: 16 x 16 cells, K = 20, 2 x 2 tiles, seed 3, each camera's own kernel): the design's usable
range, the plane count, the resolvable steps and the depth resolution at both ends, from the
`sweep` of pinmask.depthmap's result on a 256 x 256 capture.
Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_defaults.py"""
import pathlib
import sys

import numpy as np

import pinmask

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "python"))
import depth_scenes as ds  # noqa: E402


def main():
    print("| camera | usable range (m) | planes | one pixel of change (1/m) | Cramer-Rao FWHM at "
          "20000 e (1/m) | depth resolution at the ends (m) |")
    print("|---|---|---|---|---|---|")
    for name, (cam, _, _) in ds.CAMERAS.items():
        camera = pinmask.Camera(**cam)
        mask = pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                                camera=camera)
        # The choice depends on the camera and the frame's size only, not on what was captured.
        capture = ds.texture(256, 256, np.random.default_rng(1))
        s = pinmask.depthmap(capture, mask, window=31)["sweep"]
        far = s["to_m"] if s["to_m"] is not None else float("inf")
        rfar = s["depth_resolution_far_m"]
        print(f"| {name} | {s['from_m']:.4g} - {far:.4g} | {s['steps']} | "
              f"{s['one_pixel_inverse_per_m']:.4f} | {s['crb_fwhm_inverse_per_m']:.4f} | "
              f"{s['depth_resolution_near_m']:.3g}, "
              f"{rfar if rfar is None else format(rfar, '.3g')} |")


if __name__ == "__main__":
    main()
