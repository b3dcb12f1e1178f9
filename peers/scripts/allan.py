#!/usr/bin/env python3
"""Allan deviation of `dtg-vib allan` against allantools (not part of the test suite).

Subcommands:
  compare  run `dtg-vib allan --json` on a record (and, with --model, `dtg-vib
           compensate`), compute allantools.oadev of the same series at the same τ,
           print the largest relative difference per series family and fail above
           --tolerance (default 1e-9).
  fixture  print allantools.oadev of a fixed deterministic series (a linear
           congruential generator plus a ramp): the numbers the Rust test
           `agrees_with_allantools_on_a_fixed_series` (crates/nav-sensors/tests/allan.rs)
           holds, so that the tests need no Python.

Series compared (the ones `dtg-vib allan` analyses):
  before, no model: the record's gyro columns as given, and the parity residues
      K0..K5 (eq. 6) computed here from them;
  after, with --model: the columns `dtg-vib compensate` writes (the series
      `allan` calls "after", same rows) and their residues.
The "before" of a model (calibrated, rate reference removed) has no file of its own;
it goes through the same Rust function as the two above.
"""

import argparse
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import allantools
import numpy as np

CHANNELS = ["X", "X1", "Y", "Y1", "Z", "Z1"]
R2 = np.sqrt(2.0)


def residues(g):
    """Eq. 6 of the paper, as nav_sensors::geometry::residues."""
    X, X1, Y, Y1, Z, Z1 = (g[c] for c in CHANNELS)
    x0, x1, x2 = X, -Z - R2 * Y1, Y + R2 * Z1
    y0, y1, y2 = Y, Z + R2 * X1, X - R2 * Z1
    z1, z2 = Y - R2 * X1, -X - R2 * Y1
    return {"K0": x0 - x1, "K1": x0 - x2, "K2": y0 - y1, "K3": x1 - x2, "K4": y1 - y2, "K5": z1 - z2}


def read_gyros(path):
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header = [h.strip() for h in rows[0]]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    t = data[:, header.index("t")]
    return float(np.median(np.diff(t))), {c: data[:, header.index(c)] for c in CHANNELS}


def oadev(y, tau0, taus):
    rate = 1.0 / tau0
    t, ad, _, _ = allantools.oadev(np.asarray(y), rate=rate, data_type="freq", taus=np.asarray(taus))
    if not np.allclose(t, taus, rtol=1e-12):
        raise SystemExit(f"allantools used τ {t}, not {taus}")
    return ad


def compare_family(entries, key_name, series, tau0, adev_key):
    worst = 0.0
    for e in entries:
        ours = np.array(e[adev_key])
        theirs = oadev(series[e[key_name]], tau0, e["tau_s"])
        rel = np.max(np.abs(ours - theirs) / np.abs(theirs))
        worst = max(worst, rel)
    return worst


def cmd_compare(a):
    tau0, before = read_gyros(a.data)
    out = json.loads(subprocess.run([a.bin, "allan", "--data", a.data, "--json", "--quiet"],
                                    check=True, capture_output=True, text=True).stdout)
    results = {
        "before, channels": compare_family(out["channels"], "channel", before, tau0, "adev_before"),
        "before, residues": compare_family(out["residues"], "residue", residues(before), tau0, "adev_before"),
    }
    n_series = 12
    if a.model:
        with tempfile.TemporaryDirectory() as tmp:
            comp = str(Path(tmp) / "compensated.csv")
            subprocess.run([a.bin, "compensate", "--model", a.model, "--data", a.data, "--out", comp,
                            "--quiet"], check=True, capture_output=True)
            _, after = read_gyros(comp)
        out = json.loads(subprocess.run([a.bin, "allan", "--data", a.data, "--model", a.model, "--json",
                                         "--quiet"], check=True, capture_output=True, text=True).stdout)
        results["after, channels"] = compare_family(out["channels"], "channel", after, tau0, "adev_after")
        results["after, residues"] = compare_family(out["residues"], "residue", residues(after), tau0,
                                                    "adev_after")
        n_series += 12
    print(f"allantools {allantools.__version__}, numpy {np.__version__}; {a.data}"
          f"{' with ' + a.model if a.model else ''}: {n_series} series, "
          f"τ = {out['channels'][0]['tau_s'][0]} to {out['channels'][0]['tau_s'][-1]} s")
    for k, v in results.items():
        print(f"  {k:18} max relative difference {v:.2e}")
    worst = max(results.values())
    print(f"max relative difference {worst:.2e} (tolerance {a.tolerance:g})")
    return 0 if worst <= a.tolerance else 1


def fixture_series(n=1000):
    x, y = 12345, []
    for k in range(n):
        x = (1103515245 * x + 12345) % 2**31
        y.append(x / 2**31 - 0.5 + 1e-4 * k)
    return np.array(y)


def cmd_fixture(_):
    y = fixture_series()
    taus = [m * 0.02 for m in (1, 2, 4, 8, 16, 32, 64)]
    for t, v in zip(taus, oadev(y, 0.02, taus)):
        print(f"({round(t / 0.02)}, {float(v)!r}),")
    return 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("compare")
    c.add_argument("--bin", required=True, help="the dtg-vib binary")
    c.add_argument("--data", required=True)
    c.add_argument("--model")
    c.add_argument("--tolerance", type=float, default=1e-9)
    sub.add_parser("fixture")
    a = p.parse_args()
    return {"compare": cmd_compare, "fixture": cmd_fixture}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
