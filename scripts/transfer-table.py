#!/usr/bin/env python3
"""The transfer table of docs/campaign.md §6, read from `dtg-vib check
--json` output: for every model M and run R, DIR/check-M-R.json.

    scripts/transfer-table.py DIR

Columns: the share of windows outside (`outside_fraction`; in brackets the
per-axis range's alone, `outside_range_fraction`), the mean weight of the
network part (`fade_weight_mean`), the worst channel's spread after over its
rms before with the fade (`spread_after`) and without (`spread_after_unfaded`),
each channel's `mean_after` (faded), and the pooled parity residue rms (√ of
the mean of the six squares) before, after with the fade (`residues`) and
without (`residues_unfaded`). A second table gives every channel's spread
after over its rms before (fade on), and each model's window signals."""
import json, math, os, sys

MODELS = ("z", "xyz", "xyz-effects", "xyz-az")
RUNS = ("x-axis", "y-axis", "z-axis", "flight")


def pooled(residues, key):
    return math.sqrt(sum(r[key] ** 2 for r in residues) / len(residues))


def worst(channels, key):
    c = max(channels, key=lambda c: c[key] / c["rms_before"])
    return f"{c[key] / c['rms_before']:.3f} ({c['channel']})"


d = sys.argv[1] if len(sys.argv) > 1 else "."
print("| model | checked on | outside (per-axis range) | mean weight | worst spread after / rms before, fade | no fade "
      "| mean after (deg/h), fade | pooled residue rms before → after, fade | no fade |")
print("|---|---|---|---|---|---|---|---|---|")
for m in MODELS:
    for r in RUNS:
        j = json.load(open(os.path.join(d, f"check-{m}-{r}.json")))
        ch = j["channels"]
        means = ", ".join(f"{c['channel']} {c['mean_after']:+.2f}" for c in ch)
        print(f"| {m} | {r} | {100 * j['outside_fraction']:.1f}% ({100 * j['outside_range_fraction']:.1f}%) "
              f"| {j['fade_weight_mean']:.3f} | {worst(ch, 'spread_after')} | {worst(ch, 'spread_after_unfaded')} "
              f"| {means} | {pooled(j['residues'], 'rms_before'):.2f} → {pooled(j['residues'], 'rms_after'):.2f} "
              f"| {pooled(j['residues_unfaded'], 'rms_after'):.2f} |")

print()
print("| model | window | checked on | " + " | ".join(c["channel"] for c in json.load(open(os.path.join(d, "check-z-x-axis.json")))["channels"]) + " |")
print("|---|---|---|" + "---|" * 6)
for m in MODELS:
    window = ",".join(json.load(open(os.path.join(d, f"{m}.json")))["model"]["preprocess"]["window"]["signals"])
    for r in RUNS:
        ch = json.load(open(os.path.join(d, f"check-{m}-{r}.json")))["channels"]
        print(f"| {m} | {window} | {r} | " + " | ".join(f"{c['spread_after'] / c['rms_before']:.3f}" for c in ch) + " |")
