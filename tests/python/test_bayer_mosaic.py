"""A Bayer mosaic saved as an image file and a PSF at the sensor's full resolution (core/image/
mosaic.hpp): read_image(bayer=) and decode_batch(bayer=) read and refuse as `decode --bayer`
does, and the command's 2 x 2 binning of a full-resolution PSF equals numpy's."""
import numpy as np
import pytest

import pinmask


def sums(a):
    r, c = a.shape[0] // 2 * 2, a.shape[1] // 2 * 2
    return a[:r, :c].reshape(r // 2, 2, c // 2, 2).sum(axis=(1, 3))


@pytest.fixture
def files(tmp_path):
    rng = np.random.default_rng(3)
    mosaic = rng.random((25, 33))  # an odd last row and column: dropped
    np.save(tmp_path / "mosaic.npy", mosaic)
    pinmask.write_image(str(tmp_path / "mosaic.tiff"), mosaic)
    np.save(tmp_path / "rgb.npy", rng.random((24, 32, 3)))
    psf = np.zeros((24, 32))
    psf[3, 5], psf[10, 20], psf[17, 9] = 1.0, 0.5, 0.7
    np.save(tmp_path / "psf.npy", psf)
    return tmp_path, mosaic, psf


def test_read_image_takes_a_mosaic_file_only_when_asked(files):
    d, mosaic, _ = files
    plain, _ = pinmask.read_image(str(d / "mosaic.npy"))
    np.testing.assert_array_equal(plain, mosaic)  # bayer=None: the file as it is
    binned, full_scale = pinmask.read_image(str(d / "mosaic.npy"), bayer="sum2x2")
    assert binned.shape == (12, 16)
    np.testing.assert_allclose(binned, sums(mosaic), rtol=1e-15)
    assert full_scale == 4.0
    np.testing.assert_allclose(pinmask.read_image(str(d / "mosaic.tiff"), bayer="sum2x2")[0],
                               sums(mosaic.astype(np.float32).astype(float)), rtol=1e-6)


@pytest.mark.parametrize("name,bayer,needle", [
    ("mosaic.npy", "green", "colour-filter pattern"), ("mosaic.tiff", "r", "only sum2x2"),
    ("mosaic.npy", "b", "bayer"), ("rgb.npy", "sum2x2", "not a mosaic"),
    ("mosaic.npy", "cyan", "bayer")])
def test_read_image_refuses_what_cannot_apply(files, name, bayer, needle):
    d, _, _ = files
    with pytest.raises(ValueError, match=needle):
        pinmask.read_image(str(d / name), bayer=bayer)
    with pytest.raises(ValueError, match=needle):
        pinmask.decode_batch([str(d / name)], bayer=bayer, psf=np.ones((3, 3)))


def test_cli_bins_a_full_resolution_psf_as_the_capture(cli, files):
    d, mosaic, psf = files
    p = cli.run("decode", "mosaic.npy", "--bayer", "sum2x2", "--psf", "psf.npy", "--nsr", "0.01",
                "--model", "linear", "-o", "x.npy")
    assert "its 2 x 2 blocks summed as the capture's" in p.stderr
    ours = pinmask.decode(sums(mosaic), psf=sums(psf), nsr=0.01, model="linear")["image"]
    np.testing.assert_allclose(np.load(d / "x.npy"), ours, rtol=0,
                               atol=1e-6 * np.abs(ours).max())
    assert "--bayer = green" in cli.error("decode", "mosaic.npy", "--bayer", "green", "--psf",
                                          "psf.npy", "-o", "y.npy")
