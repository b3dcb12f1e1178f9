#!/usr/bin/env python3
"""RBFRegressor.fit's time against the `rbf fit` command's `fit_seconds` on the
same data and settings (issue 36 §2: within 10 %).

The command times its library call alone (`fit_seconds` of `rbf fit --json`); the
Python time is the whole `est.fit(X, y)` call: scikit-learn's input validation, the
copy into the library's matrices and the fitted attributes included. The two run
alternately, REPS times each, and the medians are compared. Measure on a quiet
machine (the figure is not asserted by any test; `--quick` is, for running):

    python python/bench/fit_time.py --rbf target/release/rbf
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rbf_dtg import RBFRegressor

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))
from conftest import friedman, write_csv  # noqa: E402

SETTINGS = [
    {"centers": "ols", "max_centers": 100},
    {"centers": "kmeans", "max_centers": 100},
    {"centers": "all", "ridge": 1e-6},
]
FLAGS = {"centers": "--centers", "max_centers": "--max-centers", "ridge": "--ridge"}


def cli_seconds(rbf, csv, names, params, out):
    cmd = [str(rbf), "fit", "--data", str(csv), "--target", "y", "--inputs", ",".join(names),
           "--split-column", "split", "--out", str(out), "--json", "--quiet"]
    for k, v in params.items():
        cmd += [FLAGS[k], str(v)]
    r = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return json.loads(r.stdout)["fit_seconds"]


def python_seconds(X, y, params):
    est = RBFRegressor(**params)
    start = time.perf_counter()
    est.fit(X, y)
    return time.perf_counter() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rbf", default=str(HERE.parents[1] / "target" / "release" / "rbf"))
    ap.add_argument("--rows", type=int, default=4000, help="training rows (all rows: 4/3 of this)")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="a small run that checks the harness")
    a = ap.parse_args()
    rows, reps = (300, 1) if a.quick else (a.rows, a.reps)
    n = rows * 4 // 3
    X, y = friedman(n, d=5, seed=3)
    split = np.where(np.arange(n) % 4 == 3, "val", "train")
    train = split == "train"
    with tempfile.TemporaryDirectory() as tmp:
        csv = Path(tmp) / "data.csv"
        names = write_csv(csv, X, y, split)
        print(f"{train.sum()} training rows × 5 inputs, {reps} alternating runs each, medians "
              f"(faer threads: {os.cpu_count()} cores)")
        print(f"{'settings':<34} {'rbf fit_seconds':>16} {'Python fit':>12} {'ratio':>7}")
        for params in SETTINGS:
            cli, py = [], []
            for _ in range(reps):
                cli.append(cli_seconds(a.rbf, csv, names, params, Path(tmp) / "m.json"))
                py.append(python_seconds(X[train], y[train], params))
            c, p = statistics.median(cli), statistics.median(py)
            label = ", ".join(f"{k}={v}" for k, v in params.items())
            print(f"{label:<34} {c:>15.4f}s {p:>11.4f}s {p / c:>7.3f}")


if __name__ == "__main__":
    main()
