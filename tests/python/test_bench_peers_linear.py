"""scripts/bench_peers_linear.py (bench-peers' comparison with LenslessPiCam's ADMM): its
renderer and truth window against a direct sum, its PSNR rule, and the skip without a checkout.
No LenslessPiCam and no torch needed."""
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts"))
import bench_peers_linear as bpl  # noqa: E402


def direct_valid(scene, psf):
    """'valid' convolution by its definition: out[i, j] = sum_k scene[i + K - 1 - k] psf[k]."""
    pr, pc = psf.shape
    out = np.zeros((scene.shape[0] - pr + 1, scene.shape[1] - pc + 1))
    for i in range(out.shape[0]):
        for j in range(out.shape[1]):
            out[i, j] = np.sum(scene[i:i + pr, j:j + pc] * psf[::-1, ::-1])
    return out


def test_render_is_the_valid_convolution():
    rng = np.random.default_rng(1)
    scene, psf = rng.random((9, 11)), rng.random((5, 6))
    got = bpl.render(psf, scene, 300.0, 2)  # 300 dB: the noise is below the rounding
    np.testing.assert_allclose(got, direct_valid(scene, psf), rtol=1e-10, atol=1e-12)


def test_truth_is_what_a_centred_impulse_images():
    # A PSF that is one impulse at element (r // 2, c // 2) images the truth window exactly.
    for r, c in ((6, 8), (7, 9), (6, 9)):
        psf = np.zeros((r, c))
        psf[r // 2, c // 2] = 1.0
        orig = bpl.photograph
        bpl.photograph = lambda name, rows, cols: np.random.default_rng(3).random((rows, cols))
        try:
            prob = bpl.make_problem("t", psf, "unused", 4)
        finally:
            bpl.photograph = orig
        clean = bpl.render(psf, np.random.default_rng(3).random((2 * r - 1, 2 * c - 1)), 300.0, 4)
        np.testing.assert_allclose(clean, prob["truth"], atol=1e-12)


def test_fit_psnr_takes_the_gain_and_the_shift():
    rng = np.random.default_rng(5)
    truth = rng.random((20, 30))
    shifted = np.roll(truth, (1, -1), axis=(0, 1))  # x[i + 1, j - 1] = truth[i, j]
    q, shift = bpl.fit_psnr(3.0 * shifted, truth)
    assert shift == (1, -1)
    assert q > 200.0
    noisy = truth + rng.normal(0.0, 0.1, truth.shape)
    q, _ = bpl.fit_psnr(noisy, truth)
    core = (slice(1, -1), slice(1, -1))
    gain = np.vdot(noisy[core], truth[core]) / np.vdot(noisy[core], noisy[core])
    want = 10 * np.log10(1.0 / np.mean((gain * noisy[core] - truth[core]) ** 2))
    assert abs(q - want) < 1e-9


def test_without_a_checkout_the_comparison_is_skipped_with_a_message():
    lines = []
    assert bpl.run(None, None, 10, out=lines.append) == []
    assert len(lines) == 1 and "--lenslesspicam" in lines[0] and "skipped" in lines[0]


def test_problem_sigma_is_the_rendered_noise():
    # make_problem's sigma is the standard deviation of the noise render added: capture minus the
    # noiseless valid convolution (by its definition) has that spread.
    rng = np.random.default_rng(6)
    psf = rng.random((4, 5))
    scene = rng.random((2 * 60 - 1, 2 * 70 - 1))
    orig = bpl.photograph
    bpl.photograph = lambda name, rows, cols: scene
    try:
        prob = bpl.make_problem("t", np.pad(psf, ((28, 28), (32, 33))), "unused", 7)
    finally:
        bpl.photograph = orig
    noise = prob["capture"] - direct_valid(scene, np.pad(psf, ((28, 28), (32, 33))))
    clean_rms = np.sqrt(np.mean((prob["capture"] - noise) ** 2))
    assert abs(prob["sigma"] - clean_rms * 10 ** (-bpl.SNR_DB / 20)) < 1e-12 * clean_rms
    assert abs(noise.std() / prob["sigma"] - 1.0) < 0.05  # 4200 samples: 2 % standard error
