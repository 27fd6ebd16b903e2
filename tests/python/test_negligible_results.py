"""Results that are all zero or black are said, never a silent success: subnormal photon levels
and full wells give an all-zero capture, a huge NSR an all-zero estimate, a tiny --scale a black
PNG; each run still exits 0 and writes its files, with a warning naming the cause."""


def test_all_zero_capture_estimate_and_black_png_are_warned(cli, tmp_path):
    cli.run("generate", "--grid", "8", "--holes", "6", "--spacing", "1", "-o", "m.mask.json")
    cli.run("simulate", "m.mask.json", "--snr", "40", "-o", "c.npy")
    for flags in (["--photons", "1e-320"], ["--photons", "20", "--full-well", "1e-320"]):
        p = cli.run("simulate", "m.mask.json", *flags, "-o", "z.npy")
        assert "the capture is all zero" in p.stderr, (flags, p.stderr)
    p = cli.run("simulate", "m.mask.json", "--photons", "200", "-o", "ok.npy")
    assert "warning" not in p.stderr
    p = cli.run("decode", "c.npy", "--mask", "m.mask.json", "--nsr", "1e308", "-o", "d.npy")
    assert "the estimate is all zero" in p.stderr and "--nsr" in p.stderr, p.stderr
    p = cli.run("decode", "c.npy", "--mask", "m.mask.json", "--scale", "1e-320", "-o", "d.png")
    assert "every pixel rounds to 0" in p.stderr, p.stderr
    p = cli.run("decode", "c.npy", "--mask", "m.mask.json", "-o", "fine.png")
    assert "warning" not in p.stderr, p.stderr
