"""Metrics: the module against `pinmask compare --json`, and independent numpy references."""
import json
import math

import numpy as np
import pytest

import pinmask

ROW_KEYS = ["max_sidelobe", "peak_to_sidelobe_ratio", "min_abs_pattern_spectrum",
            "spectral_flatness", "otf_condition_number", "analytic_wiener_psnr_db",
            "analytic_mmse_psnr_db", "analytic_wiener_nsr", "sim_wiener_psnr_db",
            "sim_wiener_ssim", "sim_wiener_nsr", "sim_tv_psnr_db", "sim_tv_ssim", "sim_tv_lambda",
            "spacing_violations", "geometry_hash", "period_px"]


def same(a, b):
    if b is None:  # the CLI writes null for an infinite value
        return math.isinf(a) or math.isnan(a)
    return a == b


def test_metrics_equal_cli_compare(cli, tmp_path, mask7):
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("compare", "m.mask.json", "--tv-iters", "50", "--json").stdout)
    row = pinmask.metrics(str(tmp_path / "m.mask.json"), tv_iterations=50)
    cli_row = j["masks"][0]
    for k in ROW_KEYS:
        assert same(row[k], cli_row[k]), (k, row[k], cli_row[k])
    # score and compare share one metric set and one prior: the same analytic figures.
    s = json.loads(cli.run("score", "m.mask.json", "--nsr", "tuned", "--json").stdout)["masks"][0]
    assert row["analytic_wiener_psnr_db"] == s["analytic_wiener_psnr_db_snr30"]
    assert row["analytic_mmse_psnr_db"] == s["analytic_mmse_psnr_db_snr30"]


def test_sidelobes_and_autocorrelation_against_numpy(mask7):
    occ = mask7.pattern.occupancy().astype(float)
    ref = np.rint(np.real(np.fft.ifft2(np.abs(np.fft.fft2(occ)) ** 2))).astype(int)
    r = pinmask.autocorrelation(mask7.pattern)
    # R(d) = #{pairs with p_j - p_i = d}: the circular autocorrelation of the occupancy.
    assert np.array_equal(r, ref)
    assert r[0, 0] == 20 and r.sum() == 20 * 20
    s = pinmask.sidelobes(mask7.pattern)
    side = ref.copy()
    side[0, 0] = 0
    assert s["peak"] == 20 and s["max_sidelobe"] == side.max()
    assert s["integrated_sidelobe_level"] == pytest.approx((side ** 2).sum() / 400, rel=1e-12)


def test_spectrum_metrics_against_numpy(mask7):
    occ = mask7.pattern.occupancy().astype(float)
    mag = np.abs(np.fft.fft2(occ)).ravel()[1:]
    s = pinmask.spectrum_metrics(mask7.pattern)
    zero_tol = 1e-9 * 20  # optimize/metrics/spectrum_metrics.hpp: |P^| <= 1e-9 K counts as zero
    expect_min = 0.0 if mag.min() <= zero_tol else mag.min()
    assert s["min_abs_pattern_spectrum"] == pytest.approx(expect_min, abs=1e-9)
    assert s["light_gain"] == 20 and s["open_fraction"] == pytest.approx(20 / 256)


def test_analytic_error_behaves(mask7):
    lo = pinmask.analytic_error(mask7, snr_db=20)
    hi = pinmask.analytic_error(mask7, snr_db=40)
    assert hi["psnr_db"] > lo["psnr_db"]
    assert lo["psnr_db"] == pytest.approx(10 * math.log10(1 / lo["mse"]), rel=1e-12)
    fixed = pinmask.analytic_error(mask7, snr_db=30, filter="nsr:0.01")
    tuned = pinmask.analytic_error(mask7, snr_db=30, filter="tuned")
    optimal = pinmask.analytic_error(mask7, snr_db=30)
    # The per-frequency optimal filter is the MMSE filter: no fixed NSR beats it.
    assert optimal["mse"] <= tuned["mse"] * (1 + 1e-12) <= fixed["mse"] * (1 + 1e-12)
    photon = pinmask.analytic_error(mask7, photons=1000, read_noise=5)
    assert photon["noise_variance"] > 0
    with pytest.raises(ValueError, match="^filter = best"):
        pinmask.analytic_error(mask7, filter="best")


def test_simulated_quality(mask7):
    q = pinmask.simulated_quality(mask7, scenes=["letter-R"], snr_db=30, weight="0.01")
    assert q["weight"] == 0.01 and set(q["scenes"]) == {"letter-R"}
    psnr, ssim = q["scenes"]["letter-R"]
    assert psnr == q["mean_psnr_db"] and 5 < psnr < 60 and -1 <= ssim <= 1
    with pytest.raises(ValueError, match="decoder"):
        pinmask.simulated_quality(mask7, decoder="rl")


@pytest.mark.parametrize("cli_noise,noise,key", [
    (["--snr", "30"], dict(snr_db=30), "snr30"),
    (["--photons", "1000", "--read-noise", "5"], dict(photons=1000, read_noise=5), "ph1000"),
])
def test_score_numbers_from_library_metrics(cli, tmp_path, mask7, cli_noise, noise, key):
    """`pinmask score` (the one prior score and compare share: 16 natural textures from seed
    1000; scenes letter-R, usaf, natural; NSR 0.01; noise seed 0) from analytic_error and
    simulated_quality."""
    mask7.save(str(tmp_path / "m.mask.json"))
    j = json.loads(cli.run("score", "m.mask.json", *cli_noise, "--json").stdout)["masks"][0]
    prior = dict(prior_scenes=16, prior_first_seed=1000)
    fixed = pinmask.analytic_error(mask7, filter="nsr:0.01", **prior, **noise)
    optimal = pinmask.analytic_error(mask7, filter="optimal", **prior, **noise)
    assert fixed["psnr_db"] == j[f"analytic_wiener_psnr_db_{key}"]
    assert optimal["psnr_db"] == j[f"analytic_mmse_psnr_db_{key}"]
    q = pinmask.simulated_quality(mask7, scenes=["letter-R", "usaf", "natural"], weight="0.01",
                                  seed=0, **noise)
    assert q["mean_psnr_db"] == j[f"sim_wiener_psnr_db_{key}"]
    assert q["mean_ssim"] == j[f"sim_wiener_ssim_{key}"]
    for name, (psnr, ssim) in q["scenes"].items():
        assert psnr == j["per_scene"][name][f"sim_wiener_psnr_db_{key}"]
