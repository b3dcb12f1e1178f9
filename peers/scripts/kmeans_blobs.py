#!/usr/bin/env python3
"""k-means quality peer: scikit-learn's default KMeans on 8 seeded blob data sets.

The data sets are those of crates/rbf/tests/common/blobs.rs, generated here by the same
integer recipe (SplitMix64 → uniforms → Box–Muller normals), so both sides see the same
numbers without a data file:

  set s (0..8), seed 1000 + s: K = 10 blob centres drawn uniformly in [-15, 15]^5,
  each redrawn until it is at least 10 from the ones before; N = 1000 points, point i
  in blob i mod 10, the centre plus N(0, 1) noise on each axis.

Prints one JSON line per set: sklearn's inertia (sum of squared distances, sklearn's
definition), whether every blob is one cluster, and the median fit time over --reps
runs. With --rust BIN (the `kmeans_blobs` example of crate rbf, built with
`cargo build --release -p rbf --example kmeans_blobs`), runs it in the same process
tree, alternating with sklearn rep by rep, and prints the medians and their ratio.

  python3 peers/scripts/kmeans_blobs.py                  # the reference inertias
  python3 peers/scripts/kmeans_blobs.py --rust target/release/examples/kmeans_blobs --reps 7
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time

MASK = (1 << 64) - 1
K, D, N, SIGMA, BOX, MIN_SEP = 10, 5, 1000, 1.0, 15.0, 10.0
SETS = 8


class SplitMix64:
    def __init__(self, seed):
        self.s = seed & MASK

    def next(self):
        self.s = (self.s + 0x9E3779B97F4A7C15) & MASK
        z = self.s
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def uniform(self):
        """In (0, 1): the top 53 bits, offset by half a step."""
        return ((self.next() >> 11) + 0.5) * 2.0**-53

    def normal(self):
        u1 = self.uniform()
        u2 = self.uniform()
        return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)


def blobs(s):
    rng = SplitMix64(1000 + s)
    centres = []
    while len(centres) < K:
        c = [BOX * (2.0 * rng.uniform() - 1.0) for _ in range(D)]
        if all(math.dist(c, o) >= MIN_SEP for o in centres):
            centres.append(c)
    x = [[centres[i % K][t] + SIGMA * rng.normal() for t in range(D)] for i in range(N)]
    truth = [i % K for i in range(N)]
    return x, truth


def same_partition(a, b):
    m, back = {}, {}
    for p, q in zip(a, b):
        if m.setdefault(p, q) != q or back.setdefault(q, p) != p:
            return False
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--rust", help="the kmeans_blobs example binary, to time in the same run")
    ap.add_argument("--write", help="also write the data sets as CSV files into this folder")
    args = ap.parse_args()

    import numpy as np
    import sklearn
    from sklearn.cluster import KMeans

    data = [blobs(s) for s in range(SETS)]
    if args.write:
        os.makedirs(args.write, exist_ok=True)
        for s, (x, truth) in enumerate(data):
            with open(os.path.join(args.write, f"blobs_{s}.csv"), "w") as f:
                f.write(",".join(f"x{t}" for t in range(D)) + ",blob\n")
                for row, b in zip(x, truth):
                    f.write(",".join(repr(v) for v in row) + f",{b}\n")
    arrays = [np.array(x) for x, _ in data]

    def sk_fit(s):
        # scikit-learn's defaults: init="k-means++" (greedy, 2 + ln k trials),
        # n_init="auto" (= 1 with k-means++), lloyd, tol 1e-4, max_iter 300
        return KMeans(n_clusters=K, random_state=s).fit(arrays[s])

    print(json.dumps({"sklearn": sklearn.__version__, "numpy": np.__version__,
                      "python": sys.version.split()[0]}))
    for s in range(SETS):
        km = sk_fit(s)
        print(json.dumps({"set": s, "sklearn_inertia": float(km.inertia_),
                          "all_blobs": same_partition(data[s][1], km.labels_.tolist()),
                          "n_iter": int(km.n_iter_)}))

    sk_times, rust_times = [], []
    for _ in range(args.reps):
        t0 = time.perf_counter()
        for s in range(SETS):
            sk_fit(s)
        sk_times.append(time.perf_counter() - t0)
        if args.rust:
            out = subprocess.run([args.rust], check=True, capture_output=True, text=True).stdout
            rust_times.append(json.loads(out.strip().splitlines()[-1])["seconds_all_sets"])
    summary = {"what": "fit time of all 8 sets, median of reps", "reps": args.reps,
               "sklearn_s": statistics.median(sk_times)}
    if rust_times:
        summary["rbf_s"] = statistics.median(rust_times)
        summary["ratio_rbf_over_sklearn"] = summary["rbf_s"] / summary["sklearn_s"]
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
