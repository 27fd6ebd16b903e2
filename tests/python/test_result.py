"""Results read as attributes and as mapping keys (pinmask.Result), nested ones too; to_dict()
gives plain containers; a mistyped name is an AttributeError that lists the keys."""
import pickle

import numpy as np
import pytest

import pinmask


def test_decode_result_reads_as_attributes_and_keys(mask7):
    cap = pinmask.simulate(mask7, "letter-R", snr_db=40)
    assert isinstance(cap, pinmask.Result) and cap.capture is cap["capture"]
    out = pinmask.decode(cap.capture, mask=mask7)
    assert isinstance(out, pinmask.Result) and isinstance(out, dict)
    assert out.image is out["image"]
    channel = out.channels[0]
    assert isinstance(channel, pinmask.Result)
    assert channel.auto_weight.weight == channel["auto_weight"]["weight"]
    assert "image" in dir(out) and "to_dict" in dir(out)
    with pytest.raises(AttributeError, match="no key 'imag'.*image"):
        out.imag
    plain = out.to_dict()
    assert type(plain) is dict and type(plain["channels"][0]) is dict
    assert type(plain["channels"][0]["auto_weight"]) is dict
    assert np.array_equal(plain["image"], out.image)
    again = pickle.loads(pickle.dumps(out))
    assert isinstance(again, pinmask.Result) and np.array_equal(again.image, out.image)


def test_every_dict_returning_function_returns_a_result(mask7):
    pattern = mask7.pattern
    results = [
        pinmask.optics(pinmask.paper_camera()),
        pinmask.sidelobes(pattern),
        pinmask.spectrum_metrics(pattern),
        pinmask.analytic_error(mask7, snr_db=30),
        pinmask.metrics(mask7, snr_db=30),
        pinmask.depth_fisher(mask7, object_distance_m=6.0),
    ]
    for r in results:
        assert isinstance(r, pinmask.Result), type(r)
    rows = pinmask.depth(mask7, distances=[4.0, 6.0])
    assert rows and all(isinstance(r, pinmask.Result) for r in rows)
