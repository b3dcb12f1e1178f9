#!/usr/bin/env python3
"""Polynomial-tail peer: scipy's RBFInterpolator on data offset by 1e7.

The data are those of crates/rbf/tests/poly_tail.rs, generated here by the same formula:
N = 50 points x_i = (frac(0.6180339887498949 i), frac(0.7548776662466927 i)),
y_i = sin(3 x_i0) cos(2 x_i1) + x_i0, every input shifted by OFFSET = 1e7; the test points
are t_j = (0.05 + 0.13 j, 0.9 − 0.11 j) + OFFSET for j = 0..7.

Prints scipy's predictions at the test points for each case as a JSON line; the Rust test
holds them as its reference values.

  python3 peers/scripts/rbf_offset.py
"""

import json

import numpy as np
import scipy
from scipy.interpolate import RBFInterpolator

OFFSET = 1e7
N = 50
CASES = [
    # name, scipy kernel, epsilon (= 1/β), degree
    ("thin_plate_deg1", "thin_plate_spline", 1.0, 1),
    ("cubic_deg1", "cubic", 1.0, 1),
    ("gaussian_deg2", "gaussian", 2.0, 2),
    ("gaussian_deg0", "gaussian", 2.0, 0),
]


def data():
    i = np.arange(N, dtype=float)
    x = np.column_stack([(0.6180339887498949 * i) % 1.0, (0.7548776662466927 * i) % 1.0])
    y = np.sin(3.0 * x[:, 0]) * np.cos(2.0 * x[:, 1]) + x[:, 0]
    j = np.arange(7, dtype=float)
    t = np.column_stack([0.05 + 0.13 * j, 0.9 - 0.11 * j])
    return x + OFFSET, y, t + OFFSET


def main():
    x, y, t = data()
    print(json.dumps({"scipy": scipy.__version__, "numpy": np.__version__}))
    for name, kernel, eps, degree in CASES:
        f = RBFInterpolator(x, y, kernel=kernel, epsilon=eps, degree=degree)
        print(json.dumps({"case": name, "pred": [float(v) for v in f(t)]}))


if __name__ == "__main__":
    main()
