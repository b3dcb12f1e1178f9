#!/usr/bin/env python3
"""Issue 23's Allan acceptance, read from `dtg-vib allan --json` output: for
every channel and residue, the worst ADEV after/before over τ (one sample to
a tenth of the record, the τ `allan` reports), whether ADEV after stays
within before × (1 + the relative half-width of before's interval) at every
τ, bias instability before and after, and the gain at the longest τ.

    dtg-vib allan --data REC --model MODEL --json --quiet > a.json
    scripts/never-worse.py a.json [b.json ...]

The last line of each file's table says whether every row passes."""
import json, sys


def rows(d):
    for kind, key in (("channels", "channel"), ("residues", "residue")):
        for c in d[kind]:
            yield c[key], c


for path in sys.argv[1:]:
    d = json.load(open(path))
    print(f"{path}: {d['samples']} samples, τ {d['channels'][0]['tau_s'][0]}…{d['channels'][0]['tau_s'][-1]} s, interval {d['confidence']}")
    print(f"{'':4} {'worst after/before':>18} {'at τ s':>7} {'within hw':>9} {'BI before':>10} {'BI after':>9} {'long-τ gain':>11}")
    ok_all = True
    for name, c in rows(d):
        before, after, det = c["adev_before"], c["adev_after"], c["adev_before_detail"]
        ratios = [a / b for a, b in zip(after, before)]
        bounds = [b * (1 + (h - l) / (2 * b)) for b, h, l in zip(before, det["high"], det["low"])]
        within = all(a <= bd for a, bd in zip(after, bounds))
        i = max(range(len(ratios)), key=lambda k: ratios[k])
        bi = c["bias_instability_deg_per_h"]
        bi_b, bi_a = bi.get("before"), bi.get("after")
        bi_ok = bi_b is None or bi_a is None or bi_a <= bi_b
        ok_all &= within and bi_ok
        fmt = lambda v: "—" if v is None else f"{v:.3f}"
        print(f"{name:4} {ratios[i]:>18.3f} {c['tau_s'][i]:>7.2f} {('yes' if within else 'NO'):>9} {fmt(bi_b):>10} {fmt(bi_a):>9} {after[-1] / before[-1]:>11.3f}")
    print(f"every channel and residue within its interval, bias instability not raised: {'yes' if ok_all else 'NO'}")
