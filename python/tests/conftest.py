"""Shared fixtures: the repository, the `rbf` and `dtg-vib` binaries, seeded data."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]


def _binary(name):
    """A release binary of the workspace: $RBF_DTG_BIN_DIR, else target/release."""
    folder = Path(os.environ.get("RBF_DTG_BIN_DIR", REPO / "target" / "release"))
    path = folder / name
    if path.is_file():
        return path
    message = f"{path} is missing: build it with `cargo build --release -p {'rbf-cli' if name == 'rbf' else name}`"
    # The test script builds the binaries first and sets this: a missing one is a failure there.
    if os.environ.get("RBF_DTG_REQUIRE_BINARIES"):
        pytest.fail(message)
    pytest.skip(message)


@pytest.fixture(scope="session")
def rbf_bin():
    return _binary("rbf")


@pytest.fixture(scope="session")
def dtg_vib():
    return _binary("dtg-vib")


def run(cmd, **kw):
    """Runs a command, failing the test with its stderr if it fails."""
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if r.returncode != 0:
        pytest.fail(f"{' '.join(map(str, cmd))} exited {r.returncode}: {r.stderr.strip()}")
    return r


def friedman(n, d=5, seed=7, noise=0.1):
    """Friedman's #1 regression problem on d uniform inputs (input j % d stands
    for Friedman's j-th), seeded."""
    rng = np.random.default_rng(seed)
    X = rng.uniform(0.0, 1.0, size=(n, d))
    c = [X[:, j % d] for j in range(5)]
    y = 10 * np.sin(np.pi * c[0] * c[1]) + 20 * (c[2] - 0.5) ** 2 + 10 * c[3] + 5 * c[4]
    return X, y + noise * rng.standard_normal(n)


def write_csv(path, X, y, split=None):
    """The CSV the `rbf` command reads: x0..x{d-1}, y[, split]; every number in its
    shortest round-trip form, so the command reads the bits the arrays hold."""
    names = [f"x{j}" for j in range(X.shape[1])]
    with open(path, "w") as f:
        f.write(",".join(names + ["y"] + (["split"] if split is not None else [])) + "\n")
        for i in range(len(y)):
            cells = [repr(float(v)) for v in X[i]] + [repr(float(y[i]))]
            if split is not None:
                cells.append(split[i])
            f.write(",".join(cells) + "\n")
    return names
