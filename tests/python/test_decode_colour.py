"""A colour capture decoded with one PSF for every channel keeps the scene's channel ratios under
every normalisation (--normalize l2 divides every channel by one factor, not each by its own
norm). The capture is rendered here with numpy (each channel's scene cyclically convolved with
the PSF), never by pinmask's simulate or PSF code; the reference is the scene itself."""
import numpy as np
import pytest

import pinmask

# The scene's colour: each channel a multiple of one texture.
COLOUR = (0.8, 0.5, 1.0)


def render(n=64, seed=5):
    rng = np.random.default_rng(seed)
    texture = 1.0 + rng.random((n, n))
    spots = rng.random((n, n)) ** 8  # sparse and positive; no spectral zero at this seed
    psf = spots / spots.sum()
    scene = np.stack([k * texture for k in COLOUR], axis=2)
    otf = np.fft.fft2(np.fft.ifftshift(psf))  # deconvwnr's centre floor(n / 2) at the origin
    capture = np.stack([np.real(np.fft.ifft2(np.fft.fft2(scene[:, :, c]) * otf))
                        for c in range(3)], axis=2)
    return scene, capture, psf


@pytest.mark.parametrize("normalize", ["none", "l2"])
def test_one_psf_for_every_channel_keeps_the_scenes_channel_ratios(normalize):
    scene, capture, psf = render()
    out = pinmask.decode(capture, psf=psf, method="wiener", nsr=1e-12, model="cyclic",
                         crop="none", background="none", normalize=normalize)
    estimate = np.asarray(out["image"], float)
    assert estimate.shape == scene.shape
    # One gain for every channel: the estimate is the scene times a constant.
    gains = [np.median(estimate[:, :, c] / scene[:, :, c]) for c in range(3)]
    assert max(gains) / min(gains) == pytest.approx(1.0, abs=1e-6), gains
    np.testing.assert_allclose(estimate / gains[0], scene, rtol=1e-6)
