"""decode_batch(): `pinmask decode --batch` from Python. Each result equals decode() on that
capture alone and the file the command's batch writes for it; paths (npy, RAW) are read as the
command reads them; errors name the capture or the keyword."""
import json

import numpy as np
import pytest

import pinmask


@pytest.fixture
def captures(mask7):
    return [pinmask.simulate(mask7, seed=s, snr_db=25)["capture"] for s in (1, 2, 3)]


@pytest.mark.parametrize("kw", [dict(), dict(method="tv", iters=15, nonneg=True),
                                dict(method="richardson-lucy", iters=10, crop="none")])
def test_decode_batch_equals_single_decodes(mask7, captures, tmp_path, kw):
    np.save(tmp_path / "c1.npy", captures[1])
    batch = pinmask.decode_batch([captures[0], str(tmp_path / "c1.npy"), captures[2]],
                                 mask=mask7, **kw)
    assert [r["source"] for r in batch] == ["capture 0", str(tmp_path / "c1.npy"), "capture 2"]
    for c, r in zip(captures, batch):
        one = pinmask.decode(c, mask=mask7, **kw)
        assert np.array_equal(r["image"], one["image"])
        assert r["window"] == one["window"]


def test_decode_batch_equals_the_commands_batch(cli, mask7, captures, tmp_path):
    mask7.save(str(tmp_path / "m.mask.json"))
    names = []
    for i, c in enumerate(captures):
        np.save(tmp_path / f"cap{i}.npy", c)
        names.append(f"cap{i}.npy")
    (tmp_path / "out").mkdir()
    (tmp_path / "list.txt").write_text("\n".join(names) + "\n")
    cli.run("decode", "--batch", "list.txt", "--mask", "m.mask.json", "--method", "tv",
            "--iters", "12", "--batch-format", "npy", "-o", "out")
    batch = pinmask.decode_batch([str(tmp_path / n) for n in names],
                                 mask=str(tmp_path / "m.mask.json"), method="tv", iters=12)
    for i, r in enumerate(batch):
        written = np.load(tmp_path / "out" / f"cap{i}.npy")
        assert written.shape == r["image"].shape
        np.testing.assert_allclose(written, r["image"], rtol=0, atol=1e-6 * abs(written).max())
    summary = json.loads((tmp_path / "out" / "batch-summary.json").read_text())
    assert len(summary["captures"]) == len(batch)


def test_decode_batch_with_a_psf_and_refocus(mask7, captures):
    psf = pinmask.psf(mask7)
    a = pinmask.decode_batch(captures[:2], psf=psf)
    for c, r in zip(captures, a):
        assert np.array_equal(r["image"], pinmask.decode(c, psf=psf)["image"])
    u = mask7.camera.object_distance_m * 2
    b = pinmask.decode_batch(captures[:1], mask=mask7, object_distance=u)
    assert np.array_equal(b[0]["image"],
                          pinmask.decode(captures[0], mask=mask7, object_distance=u)["image"])
    assert b[0]["refocus"]["object_distance_m"] == u


def test_decode_batch_reads_raw_as_read_image(tmp_path, source_dir):
    raw = str(source_dir / "fuzz" / "corpus" / "raw" / "small.dng")
    psf = np.zeros((4, 4))
    psf[2, 2] = 1.0  # the centre floor(size / 2), as deconvwnr places it
    for bayer in ("sum2x2", "g"):
        r = pinmask.decode_batch([raw], bayer=bayer, psf=psf, crop="none", nsr=0.0)
        image, _ = pinmask.read_image(raw, bayer=bayer)
        # A delta PSF with nsr 0 decodes to the capture itself.
        np.testing.assert_allclose(r[0]["image"], image, rtol=1e-12, atol=1e-9)


def test_decode_batch_errors(mask7, captures):
    with pytest.raises(ValueError, match="captures: the list is empty"):
        pinmask.decode_batch([], mask=mask7)
    with pytest.raises(ValueError, match="capture 0: nsr = -1"):
        pinmask.decode_batch([captures[0], captures[1]], mask=mask7, nsr=-1)
    with pytest.raises(ValueError, match="capture is not a keyword"):
        pinmask.decode_batch([captures[0]], capture=captures[0], mask=mask7)
    with pytest.raises(ValueError, match="bayer = x"):
        pinmask.decode_batch([captures[0]], bayer="x", mask=mask7)
    with pytest.raises(ValueError, match="does not exist"):
        pinmask.decode_batch(["/nonexistent/c.npy"], mask=mask7)
    with pytest.raises(TypeError):
        pinmask.decode_batch([captures[0]], mask=mask7, no_such_keyword=1)
