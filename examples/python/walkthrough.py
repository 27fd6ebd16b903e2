"""One camera from design to decode with the pinmask module, as a notebook would run it.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/walkthrough.py OUT_DIR

A small near-infrared camera (5.86 um pixels, f' = 75 mm, f = 45 mm, 850 nm, designed for
u = 1.2 m): the optics report, a search over pinhole counts 6..10, the fabrication files, a
simulated capture and its decode, a refocus to an object at 2 m, the calibration of a
simulated point-source capture and the decode's loss against object distance. Figures are
images written with pinmask.write_image (PNG) into OUT_DIR; OUT_DIR/walkthrough.json holds
every number printed. tests/python/test_walkthrough.py
runs this script and checks each figure against the command line's for the same inputs.
"""
import json
import pathlib
import sys

import numpy as np

import pinmask


def to_png(path, image):
    """An image scaled to [0, 1] (its own maximum) as an 8-bit PNG."""
    image = np.asarray(image, dtype=float)
    top = image.max()
    pinmask.write_image(str(path), np.clip(image / top if top > 0 else image, 0, 1))


def psnr_aligned(estimate, truth):
    """PSNR in dB after the least-squares gain and offset (a decode's scale is its own)."""
    a = np.stack([estimate.ravel(), np.ones(estimate.size)], axis=1)
    coef, *_ = np.linalg.lstsq(a, truth.ravel(), rcond=None)
    return float(10 * np.log10(1.0 / np.mean((a @ coef - truth.ravel()) ** 2)))


def main(out):
    out.mkdir(parents=True, exist_ok=True)
    summary = {}

    # 1. Design: the camera, its optics at the working distance, saved as a camera file.
    camera = pinmask.Camera(pixel_pitch_m="5.86um", sensor_cols=640, sensor_rows=480,
                            lens_focal_m="75mm", sensor_distance_m="45mm",
                            object_distance_m="1.2m", wavelength_m="850nm", pinhole_m="120um")
    pinmask.save_camera(camera, str(out / "nir.camera.json"))
    optics = pinmask.optics(camera, grid=8, holes=6)
    summary["pixels_per_cell"] = optics["pixels_per_cell"]
    print(f"optics: {optics['pixels_per_cell']:.3f} px per cell at u = 1.2 m")

    # 2. Search: 8 x 8 cells, 6..10 pinholes, a fixed number of evaluations (deterministic).
    result = pinmask.search(camera=camera, grid=8, holes="6..10", evals=300, threads=1, seed=3,
                            top=1, rerank_scenes=[])
    mask = result["masks"][0]
    mask.save(str(out / "best.mask.json"))
    summary["holes"] = len(mask.pattern.pinholes)
    summary["objective"] = result["ranked"][0]["objective"]
    print(f"search: {summary['holes']} pinholes, objective {summary['objective']:.4f}")

    # 3. Export: fabrication files (read back before they are written).
    exported = pinmask.export_mask(mask, str(out / "fab"), formats=["svg", "gds"], stem="best")
    summary["export_files"] = sorted(f["name"] for f in exported["files"])

    # 4. Simulate a capture of the letter R at 40 dB SNR; 5. decode it (Wiener).
    psf = pinmask.psf(mask)
    sim = pinmask.simulate(mask, "letter-R", snr_db=40, seed=1)
    decoded = pinmask.decode(sim["capture"], mask=mask, method="wiener", nsr=1e-3)["image"]
    truth = pinmask.scene("letter-R", *decoded.shape)
    summary["decode_psnr_db"] = psnr_aligned(decoded, truth)
    np.save(out / "capture.npy", sim["capture"])
    np.save(out / "decoded.npy", decoded)
    to_png(out / "psf.png", psf)
    to_png(out / "capture.png", sim["capture"])
    to_png(out / "decoded.png", decoded)
    print(f"decode: {summary['decode_psnr_db']:.2f} dB")

    # 6. Refocus: an object at 2 m, exact geometry over a 240 x 320 window, decoded with the
    # PSF at 2 m (the exact PSF over the frame when the pitch there is not whole).
    far = pinmask.simulate(mask, "letter-R", snr_db=40, seed=1, geometry="exact",
                           object_distance="2m", size=(240, 320))
    refocused = pinmask.decode(far["capture"], mask=mask, object_distance="2m", nsr=1e-3)
    summary["refocus"] = refocused["refocus"]
    np.save(out / "refocus-capture.npy", far["capture"])
    np.save(out / "refocused.npy", refocused["image"])
    to_png(out / "refocus-capture.png", far["capture"])
    to_png(out / "refocused.png", refocused["image"])
    print(f"refocus at 2 m: pitch {refocused['refocus']['pitch_px']:.3f} px, "
          f"{refocused['refocus']['geometry']} geometry")

    # 7. Calibrate: what the sensor records from a point source at the design distance (the
    # exact-geometry PSF over the sensor with the mask's diffraction kernel, scaled to counts,
    # with read noise), fitted back. (A box kernel, each spot the pinhole's geometric shadow, is
    # not this camera's light: at 9 px per cell the spots are diffraction-shaped, and calibrate
    # refuses such a capture as unexplained by the mask's model.)
    rng = np.random.default_rng(2)
    point = 1000 * pinmask.psf(mask, geometry="exact", size=(200, 240))
    point = point + rng.normal(0, 0.01 * point.max(), point.shape)
    np.save(out / "point.npy", point)
    cal = pinmask.calibrate(point, mask)
    summary["calibrate"] = {"rotation_deg": cal["rotation_deg"], "pitch_px": list(cal["pitch_px"])}
    print(f"calibrate: {summary['calibrate']}")

    # 8. Depth: the Wiener decode's loss against object distance (the mask decoded at its
    # design distance), dim light: 200 electrons per pinhole, 6 e- read noise, the tuned NSR.
    rows = pinmask.depth(mask, from_m=0.9, to_m=2.0, steps=4, photons=200, read_noise=6,
                         tv=False)
    summary["depth"] = rows
    for r in rows:
        print(f"depth: u = {r['object_distance_m']} m: Wiener loss {r['wiener_psnr_loss_db']:.2f} dB")

    (out / "walkthrough.json").write_text(json.dumps(summary, indent=2, sort_keys=True) + "\n")


if __name__ == "__main__":
    main(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "walkthrough-out"))
