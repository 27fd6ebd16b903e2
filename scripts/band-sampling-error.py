#!/usr/bin/env python3
"""How closely the camera's band sampling (design/optics/spectrum: a Gaussian of FWHM B at 13
wavelengths over +-1.5 FWHM) follows the band: the L1 distance of the mask's PSF from the PSF of
a 241-sample Gaussian over +-3 FWHM, beside that of 7 samples over +-1.5 FWHM and that of the
one-wavelength PSF (the band's whole effect). Three cameras; the figures are quoted in docs/commands.md.

Run: PYTHONPATH=build/python /usr/bin/python3 scripts/band-sampling-error.py
"""
import numpy as np

import pinmask

FIELDS = ["object_distance_m", "lens_focal_m", "sensor_distance_m", "wavelength_m",
          "pixel_pitch_m", "pinhole_m", "sensor_cols", "sensor_rows"]


def gaussian_band(lam, fwhm, n, span):
    x = np.linspace(-span * fwhm, span * fwhm, n)
    w = np.exp(-4 * np.log(2) * x**2 / fwhm**2)  # half the peak at +-fwhm/2
    return [(float(lam + a), float(b)) for a, b in zip(x, w / w.sum())]


def measure(name, camera):
    mask = pinmask.generate(seed=3, camera=camera)
    band = pinmask.psf(mask)
    mask.camera = pinmask.Camera(**{k: getattr(camera, k) for k in FIELDS})  # bandwidth 0
    one = pinmask.psf(mask)
    mask.wavelengths = gaussian_band(camera.wavelength_m, camera.bandwidth_m, 241, 3.0)
    ref = pinmask.psf(mask)
    mask.wavelengths = gaussian_band(camera.wavelength_m, camera.bandwidth_m, 7, 1.5)
    seven = pinmask.psf(mask)  # the coarser rule: 7 samples B/2 apart over +-1.5 FWHM
    l1 = lambda a: f"{np.abs(a - ref).sum():.2e}"
    print(f"{name}: PSF {band.shape[0]} px, L1 from 241 samples: 13 samples {l1(band)}, "
          f"7 samples {l1(seven)}, one wavelength {l1(one)}")


measure("NIR 850 nm, FWHM 30 nm", pinmask.Camera(
    pixel_pitch_m="5.86um", sensor_cols=1920, sensor_rows=1200, lens_focal_m="75mm",
    sensor_distance_m="45mm", object_distance_m="1.2m", wavelength_m="850nm",
    pinhole_m="455.406um", bandwidth_m="30nm"))
measure("paper 550 nm, FWHM 60 nm", pinmask.Camera(bandwidth_m="60nm"))
measure("lensless 650 nm, FWHM 80 nm", pinmask.Camera(
    lens_focal_m="inf", sensor_distance_m="30mm", object_distance_m="3m", wavelength_m="650nm",
    pinhole_m="200um", pixel_pitch_m="20um", bandwidth_m="80nm"))
