#!/usr/bin/python3
"""Markdown table of the masks/ library from each folder's score.json (pinmask score --json)."""
import json
import pathlib
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "masks")
cols = [
    ("n", "n", "{}"), ("holes", "K", "{}"), ("geometry_hash", "hash", "`{}`"),
    ("max_sidelobe", "max sidelobe", "{}"),
    ("min_abs_pattern_spectrum", "min abs P^", "{:.3f}"),
    ("spectral_flatness", "flatness", "{:.3f}"),
    ("otf_condition_number", "OTF cond.", "{:.0f}"),
    ("analytic_wiener_psnr_db_snr30", "analytic Wiener dB @30", "{:.2f}"),
    ("analytic_wiener_psnr_db_snr40", "analytic Wiener dB @40", "{:.2f}"),
    ("wiener_psnr_db_snr30", "sim. Wiener dB @30", "{:.2f}"),
    ("wiener_psnr_db_snr40", "sim. Wiener dB @40", "{:.2f}"),
]
print("| mask | " + " | ".join(c[1] for c in cols) + " |")
print("|---|" + "---:|" * len(cols))
for score in sorted(root.glob("*/score.json")):
    row = json.loads(score.read_text())["masks"][0]
    cells = []
    for key, _, fmt in cols:
        v = row.get(key)
        cells.append("-" if v is None else fmt.format(v))
    print(f"| {score.parent.name} | " + " | ".join(cells) + " |")
