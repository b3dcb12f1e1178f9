"""RBFRegressor inside scikit-learn's tools, on DataFrames, pickled, and refusing
bad input with rbf_dtg.Error (issue 36 §2)."""

import pickle

import numpy as np
import pandas as pd
import pytest
from sklearn.model_selection import GridSearchCV, KFold, cross_val_score
from sklearn.pipeline import Pipeline
from sklearn.preprocessing import StandardScaler

import rbf_dtg
from rbf_dtg import RBFRegressor

from conftest import friedman


def test_pipeline_fits_friedman_well():
    X, y = friedman(400)
    pipe = Pipeline([("scale", StandardScaler()), ("rbf", RBFRegressor(max_centers=40))])
    pipe.fit(X[:300], y[:300])
    # Friedman #1 with noise sd 0.1 (signal sd ≈ 5): a 40-centre network explains
    # well over 90 % of the held-out variance.
    assert pipe.score(X[300:], y[300:]) > 0.9


def test_cross_val_score_and_grid_search():
    X, y = friedman(300)
    scores = cross_val_score(RBFRegressor(max_centers=20), X, y, cv=KFold(5, shuffle=True, random_state=0))
    assert scores.shape == (5,) and np.all(scores > 0.8)
    grid = GridSearchCV(RBFRegressor(), {"max_centers": [2, 30], "kernel": ["gaussian", "thin-plate"]}, cv=3)
    grid.fit(X, y)
    # two centres cannot follow Friedman's surface: the search must prefer 30
    assert grid.best_params_["max_centers"] == 30
    assert grid.best_estimator_.n_features_in_ == 5


@pytest.mark.filterwarnings("ignore:X does not have valid feature names")
def test_dataframe_in_sets_feature_names_and_checks_them():
    X, y = friedman(200)
    df = pd.DataFrame(X, columns=["a", "b", "c", "d", "e"])
    est = RBFRegressor(max_centers=10).fit(df, pd.Series(y, name="target"))
    assert list(est.feature_names_in_) == ["a", "b", "c", "d", "e"]
    with pytest.warns(UserWarning, match="does not have valid feature names"):
        np.testing.assert_array_equal(est.predict(df), est.predict(X))
    assert est.centers_.shape == (10, 5) and est.coef_.shape == (10,)
    assert est.width_.shape == (10,) and est.err_.shape == (10,)
    with pytest.raises(rbf_dtg.Error):
        est.predict(X[:, :4])


def test_fitted_attributes_reproduce_the_prediction():
    X, y = friedman(200, d=2)
    est = RBFRegressor(max_centers=12, width=0.4).fit(X, y)
    # f(x) = λ0 + Σ λᵢ exp(−‖x − cᵢ‖²/β²), the model the docs state
    d2 = ((X[:, None, :] - est.centers_[None, :, :]) ** 2).sum(axis=2)
    by_hand = est.intercept_ + np.exp(-d2 / est.width_**2) @ est.coef_
    np.testing.assert_allclose(est.predict(X), by_hand, rtol=1e-10, atol=1e-10)
    # every centre is a training row (OLS picks among them), ERRs in [0, 1]
    assert all(np.any(np.all(X == c, axis=1)) for c in est.centers_)
    assert np.all((0 <= est.err_) & (est.err_ <= 1))


def test_two_outputs_share_the_centres():
    X, y = friedman(200, d=3)
    Y = np.column_stack([y, -2 * y + 1])
    est = RBFRegressor(max_centers=15).fit(X, Y)
    assert est.predict(X).shape == (200, 2) and est.coef_.shape == (2, 15)
    np.testing.assert_allclose(est.predict(X)[:, 1], -2 * est.predict(X)[:, 0] + 1, rtol=1e-9, atol=1e-9)


def test_pickle_predicts_bit_identically():
    X, y = friedman(150)
    est = RBFRegressor(centers="kmeans", max_centers=8).fit(X, y)
    back = pickle.loads(pickle.dumps(est))
    np.testing.assert_array_equal(back.predict(X), est.predict(X))


def test_random_state_none_is_the_command_line_seed():
    X, y = friedman(150)
    a = RBFRegressor(centers="random", max_centers=8).fit(X, y)
    b = RBFRegressor(centers="random", max_centers=8, random_state=42).fit(X, y)
    c = RBFRegressor(centers="random", max_centers=8, random_state=1).fit(X, y)
    np.testing.assert_array_equal(a.centers_, b.centers_)
    assert not np.array_equal(a.centers_, c.centers_)


@pytest.mark.parametrize(
    "params, message",
    [
        # the command's own messages: a flag value out of range, a flag for another strategy,
        # more centres than the rows take (with the value that works)
        ({"centers": "best"}, "invalid value 'best' for centers: valid names: ols, kmeans, random, all"),
        ({"ridge": -1.0}, "invalid value '-1' for ridge: must be a number from 0 to 1e12"),
        ({"tol": 1.0}, "invalid value '1' for tol: must be a number from 0 up to (not including) 1"),
        ({"kernel": "box"}, "invalid value 'box' for kernel: "),
        ({"centers": "kmeans", "tol": 0.01}, "--tol applies to --centers ols only, not kmeans"),
        ({"max_centers": 60}, "60 centres asked for but 50 training rows take at most 50; use --max-centers ≤ 50"),
    ],
)
def test_bad_settings_raise_the_command_line_message(params, message):
    X, y = friedman(50)
    with pytest.raises(rbf_dtg.Error) as e:
        RBFRegressor(**params).fit(X, y)
    assert str(e.value).startswith(message), str(e.value)


def test_nan_and_missing_values_raise_error():
    X, y = friedman(50)
    X[3, 1] = np.nan
    with pytest.raises(rbf_dtg.Error, match="NaN"):
        RBFRegressor().fit(X, y)
    assert issubclass(rbf_dtg.Error, ValueError)
