"""score(): `pinmask score` from Python. The rows equal the command's --json rows (same keys,
same numbers) for a metric selection, noise seeds and the photon model; the robust decoder's
arrays equal the files score --robust-decoder writes; the sidelobes against a numpy
autocorrelation; errors name the keywords."""
import json

import numpy as np
import pytest

import pinmask


def cli_rows(cli, *args):
    return json.loads(cli.run("score", *args, "--json").stdout)


def test_score_equals_cli_score(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    path = str(tmp_path / "m.mask.json")
    for flags, kw in [
        (["--metrics", "sidelobes,wiener", "--snr", "25", "--seeds", "2"],
         dict(metrics="sidelobes,wiener", snr_db=25, noise_seeds=2)),
        (["--metrics", "spectrum,analytic,wiener", "--photons", "50,500", "--read-noise", "3",
          "--nsr", "tuned", "--scenes", "usaf,natural"],
         dict(metrics=["spectrum", "analytic", "wiener"], photons=[50, 500], read_noise=3,
              nsr="tuned", scenes=["usaf", "natural"])),
    ]:
        c = cli_rows(cli, "m.mask.json", *flags)["masks"][0]
        p = pinmask.score([path], **kw)["masks"][0]
        c["mask"] = path
        assert set(p) == set(c), sorted(set(p) ^ set(c))
        for k, v in c.items():
            if k == "spectral_zero" and v is not None:
                assert p[k]["count"] == v["count"] and list(p[k]["frequency"]) == v["frequency"]
            else:
                assert p[k] == v, (k, p[k], v)


def test_score_defaults_are_the_commands(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    c = cli_rows(cli, "m.mask.json")
    p = pinmask.score([mask7])
    assert [level["key"] for level in p["settings"]["noise"]] == ["snr20", "snr30", "snr40"]
    assert p["settings"]["scenes"] == c["settings"]["scenes"]
    cr, pr = c["masks"][0], p["masks"][0]
    for k in ("sim_wiener_psnr_db_snr30", "analytic_wiener_psnr_db_snr40", "max_sidelobe"):
        assert pr[k] == cr[k], k
    assert "sim_tv_psnr_db_snr30" not in pr  # tv is opt-in, as in the command


def test_score_sidelobes_against_numpy(mask7):
    row = pinmask.score([mask7], metrics=["sidelobes"])["masks"][0]
    n = mask7.pattern.n
    a = np.zeros((n, n))
    for r, c in mask7.pattern.pinholes:
        a[r, c] = 1.0
    f = np.fft.fft2(a)
    ac = np.rint(np.real(np.fft.ifft2(f * np.conj(f)))).astype(int)
    assert row["peak_autocorrelation"] == ac[0, 0] == len(mask7.pattern.pinholes)
    ac[0, 0] = 0
    assert row["max_sidelobe"] == ac.max()
    assert set(row) == {"mask", "geometry_hash", "n", "holes", "pixels_per_cell", "period_px",
                        "peak_autocorrelation", "max_sidelobe", "mean_sidelobe",
                        "integrated_sidelobe_level", "peak_to_sidelobe_ratio"}


def test_score_robust_decoder_equals_the_files(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    cli.run("score", "m.mask.json", "--snr", "25", "--metrics", "analytic", "--robust",
            "size=5um,missing=0.02", "--robust-decoder", "rd")
    row = pinmask.score([str(tmp_path / "m.mask.json")], metrics="analytic", snr_db=25,
                        robust="size=5um,missing=0.02", robust_decoder=True)["masks"][0]
    rd = row["robust_decoder"]
    assert np.array_equal(rd["psf"], np.load(tmp_path / "rd" / "robust-psf.npy"))
    assert np.array_equal(rd["nsr_map"], np.load(tmp_path / "rd" / "robust-nsr.npy"))
    assert "analytic_robust_wiener_loss_db_snr25" in row
    # decode reads them as it reads the files
    out = pinmask.decode(np.ones(rd["psf"].shape), psf=rd["psf"], nsr_map=rd["nsr_map"],
                         model="cyclic")  # one period of the mask (an array has no sidecar)
    assert np.isfinite(out["image"]).all()


@pytest.mark.parametrize("kw, fragment", [
    (dict(metrics="sidelobes,foo"), "metrics = foo: must be one of"),
    (dict(metrics=[]), "metrics = '': name at least one metric"),
    (dict(noise_seeds=0), "noise_seeds = 0"),
    (dict(nsr="-1"), "nsr"),
    (dict(robust_decoder=True), "robust_decoder needs robust"),
    (dict(robust="size=5um", robust_decoder=True), "one noise level"),
])
def test_score_errors_name_keywords(mask7, kw, fragment):
    with pytest.raises(ValueError) as e:
        pinmask.score([mask7], **kw)
    assert fragment in str(e.value)
    assert "--" not in str(e.value)
