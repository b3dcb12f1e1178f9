"""RBFRegressor gives the `rbf fit` command's model: on the same data and settings,
the same centres (the same OLS picks), and predictions equal within 1e-12 relative
(issue 36 §2). Both sides run the same library code on the same bits (the CSV holds
each number's shortest round-trip form), so only the threads' rounding could differ."""

import json

import numpy as np
import pytest

from rbf_dtg import RBFRegressor, _native

from conftest import friedman, run, write_csv

FLAGS = {
    "centers": "--centers",
    "kernel": "--kernel",
    "width": "--width",
    "max_centers": "--max-centers",
    "ridge": "--ridge",
    "tol": "--tol",
    "degree": "--degree",
    "stop": "--stop",
    "random_state": "--seed",
}

SETTINGS = [
    {},
    {"centers": "kmeans", "max_centers": 20, "random_state": 3},
    {"centers": "random", "max_centers": 30, "width": 0.5, "degree": 1},
    {"centers": "all", "ridge": 1e-6, "kernel": "thin-plate"},
    {"stop": "press", "max_centers": 60},
    {"kernel": "multiquadric", "standardize": True, "tol": 0.01},
]


def cli_args(params):
    args = []
    for name, value in params.items():
        if name == "standardize":
            args += ["--standardize"] if value else []
        else:
            args += [FLAGS[name], str(value)]
    return args


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    X, y = friedman(600, d=4, seed=11)
    split = np.where(np.arange(600) % 4 == 3, "val", "train")
    path = tmp_path_factory.mktemp("cli") / "friedman.csv"
    names = write_csv(path, X, y, split)
    return path, names, X, y, split == "train"


@pytest.mark.parametrize("params", SETTINGS, ids=lambda p: ",".join(f"{k}={v}" for k, v in p.items()) or "defaults")
def test_same_centres_and_predictions_as_rbf_fit(rbf_bin, data, tmp_path, params):
    path, names, X, y, train = data
    model, pred = tmp_path / "m.json", tmp_path / "pred.csv"
    fit = run([rbf_bin, "fit", "--data", path, "--target", "y", "--inputs", ",".join(names),
               "--split-column", "split", "--out", model, "--json", "--quiet", *cli_args(params)])
    report = json.loads(fit.stdout)
    run([rbf_bin, "predict", "--model", model, "--data", path, "--out", pred, "--quiet"])
    cli_pred = np.loadtxt(pred, delimiter=",", skiprows=1, usecols=0)
    cli_model, inputs, target = _native.RbfModel.load(str(model))

    est = RBFRegressor(**params).fit(X[train], y[train])

    assert est.centers_.shape[0] == report["n_centers"]
    np.testing.assert_array_equal(est.centers_, cli_model.centres)
    if cli_model.picks is not None:
        assert [p[0] for p in est._model.picks] == [p[0] for p in cli_model.picks]
    ours = est.predict(X)
    np.testing.assert_allclose(ours, cli_pred, rtol=1e-12, atol=0)
    # and the command reads the estimator's own model file to the same numbers
    est.save(tmp_path / "ours.json")
    run([rbf_bin, "predict", "--model", tmp_path / "ours.json", "--data", path, "--out", tmp_path / "p2.csv", "--quiet"])
    np.testing.assert_array_equal(np.loadtxt(tmp_path / "p2.csv", delimiter=",", skiprows=1, usecols=0), ours)
