#!/usr/bin/python3
"""The four-camera table of docs/depth.md (section 3a): pinmask.depthmap with its defaults
(window 121, smoothing 8, NSR 0.01) over 16 planes spanning each camera's range, on scenes
rendered by the independent numpy model of tests/python/depth_scenes.py (box spots), photons
2000, seed 1, 384 x 384: the scenes of SCENE_KINDS and one plane at five range positions.
tests/python/test_depthmap_cameras.py holds every row. Run from the repository:
PYTHONPATH=build/python /usr/bin/python3 scripts/depthmap_cameras.py [KERNEL]
KERNEL: the masks' kernel model, box (default: the renderer's spot, so only the method is
measured) or auto (each mask's own diffraction kernel against the renderer's box spots)."""
import pathlib
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import depth_scenes as ds  # noqa: E402
import pinmask  # noqa: E402

KERNEL = sys.argv[1] if len(sys.argv) > 1 else "box"
SCENES = [(k, 384) for k in ds.SCENE_KINDS] + [(t, 384) for t in (0.1, 0.3, 0.5, 0.7, 0.9)]


def fmt(x, pattern):
    return "-" if x is None else pattern.format(x)


print("| camera | scene | within one spacing | RMS (spacings) | median error (spacings) | "
      "share at confidence >= 0.5 | within one spacing there | flat region's median "
      "confidence | all-in-focus PSNR (dB) | true-PSF decode PSNR (dB) | whole capture: "
      "cost, evidence (error, spacings) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as tmp:
    for name, (cam, near, far) in ds.CAMERAS.items():
        mask = pathlib.Path(tmp) / "m.mask.json"
        pinmask.generate(family="random", grid=16, holes=20, spacing=2, tiles=2, seed=3,
                         camera=pinmask.Camera(**cam), kernel=KERNEL).save(str(mask))
        loaded = pinmask.load_mask(str(mask))
        run = lambda c, a, b, n: pinmask.depthmap(c, loaded, from_m=a, to_m=b, steps=n)
        for scene, size in SCENES:
            r = ds.measure_kind(run, mask, scene, near, far, 16, size, 2000.0, 1)
            label = (f"one plane, {1 / ds.range_inverse(near, far, scene):.3g} m"
                     if isinstance(scene, float) else scene)
            print(f"| {name} | {label} | {100 * r['within_spacing']:.0f} % | "
                  f"{r['rms_planes']:.2f} | {r['median_error_planes']:+.2f} | "
                  f"{100 * r['confident_share']:.0f} % | "
                  f"{fmt(r['within_when_confident'], '{:.0%}')} | "
                  f"{fmt(r['flat_confidence_median'], '{:.2f}')} | {r['aif_psnr_db']:.2f} | "
                  f"{r['true_psf_psnr_db']:.2f} | "
                  f"{fmt(r['capture_error_planes'], '{:.2f}')}, "
                  f"{fmt(r['evidence_error_planes'], '{:.2f}')} |", flush=True)
