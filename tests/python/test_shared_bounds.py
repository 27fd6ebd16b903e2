"""The module and the command line share their bounds: each is defined once, in the library
validator both faces call (SearchOptions::kMaxEvaluations, SimulatedMetricsOptions::
kMaxNoiseSeeds), so a request the command line refuses is refused from Python too, with the same
rule, before any work (search(evals=10**12) used to run forever, simulated_quality with 10^9
noise seeds to 15 GB)."""
import pinmask
import pytest


def test_search_evaluations_bound(cli):
    msg = cli.error("search", "--evals", "1000000000000", "-o", "s")
    with pytest.raises(ValueError) as e:
        pinmask.search(evals=10**12)
    rule = "to 1e9 evaluations per chain"
    assert rule in msg and rule in str(e.value)
    assert str(e.value).startswith("evals = 1000000000000: ")


def test_noise_seeds_bound(cli, mask7):
    (cli.cwd / "m.mask.json").write_text(mask7.to_json())
    msg = cli.error("score", "m.mask.json", "--seeds", "1000000000")
    with pytest.raises(ValueError) as e:
        pinmask.simulated_quality(mask7, noise_seeds=10**9, snr_db=30)
    rule = "must be between 1 and 1000"
    assert rule in msg and rule in str(e.value)
    # The largest accepted value is the same on both faces.
    with pytest.raises(ValueError):
        pinmask.simulated_quality(mask7, noise_seeds=1001, snr_db=30)
