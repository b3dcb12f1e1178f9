"""The RBF library as a scikit-learn regressor.

The fit is the ``rbf fit`` command's (``crates/rbf-cli``): the parameters map one
to one onto its flags, are checked by its parsers and refused with its messages,
and the same data and settings give the same centres and predictions.
"""

import numbers

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils import check_random_state
from sklearn.utils.validation import check_is_fitted, validate_data

from . import _native
from ._native import Error
from ._refusals import refusals

# random_state=None takes the command line's default seed: fits are reproducible.
CLI_SEED = 42


def _seed(random_state):
    """The library's u64 seed for a scikit-learn ``random_state``."""
    if random_state is None:
        return CLI_SEED
    if isinstance(random_state, numbers.Integral):
        if random_state < 0:
            raise Error(f"invalid value '{random_state}' for random_state: must be a whole number ≥ 0")
        return int(random_state)
    return int(check_random_state(random_state).randint(np.iinfo(np.int32).max))


class RBFRegressor(RegressorMixin, BaseEstimator):
    """A radial-basis-function network f(x) = λ0 + Σᵢ λᵢ φ(‖x − cᵢ‖/β).

    Parameters map onto ``rbf fit``'s flags:

    centers : {"ols", "kmeans", "random", "all"}, default="ols"
        ``--centers``: OLS forward selection by error-reduction ratio, k-means
        centroids, a seeded random subset of the rows, or every row.
    kernel : str, default="gaussian"
        ``--kernel``: gaussian, multiquadric, inverse-multiquadric,
        inverse-quadratic, thin-plate, cubic, wendland-c2.
    width : float or None, default=None
        ``--width``: β in input units; None is ``auto`` (the median pairwise
        distance between the candidate centres; with ``stop="press"|"gcv"``, the
        best of 0.25, 0.5, 1, 2, 4 times it by PRESS).
    max_centers : int or None, default=None
        ``--max-centers``: the most centres for OLS, exactly that many for k-means
        and random. None is the command's default (50; with ``stop="press"|"gcv"``
        a tenth of the rows, 10 to 200), lowered to the most the training rows take.
    ridge : float, default=0.0
        ``--ridge``: λ on the kernel weights (``centers="all"``: smoothing).
    tol : float or None, default=None
        ``--tol`` (OLS): stop once 1 − ΣERR < tol; None runs to ``max_centers``.
    degree : int or None, default=None
        ``--degree``: polynomial tail on unit-box inputs (−1 none … 2 quadratic)
        instead of the bias.
    standardize : bool, default=False
        ``--standardize``: inputs to zero mean, unit variance (β in those units).
    stop : str or None, default=None
        ``--stop`` (OLS): "press", "gcv", "err:RHO" or "k:K".
    random_state : int, RandomState or None, default=None
        ``--seed``; None is the command's seed, 42.

    Attributes
    ----------
    centers_ : ndarray (n_centers, n_features_in_), in data units.
    coef_ : ndarray (n_centers,), or (n_outputs, n_centers) for 2-D y: the kernel weights.
    intercept_ : float, or ndarray (n_outputs,): the bias λ0 (0 when ``degree``
        replaces it by a polynomial tail).
    width_ : ndarray (n_centers,): β of each centre.
    err_ : ndarray (n_centers,) or None: OLS, the error-reduction ratio of each pick.
    condition_ : float: estimated condition number of the weights' least squares.
    n_features_in_, feature_names_in_ : as scikit-learn sets them.
    """

    def __init__(
        self,
        centers="ols",
        kernel="gaussian",
        width=None,
        max_centers=None,
        ridge=0.0,
        tol=None,
        degree=None,
        standardize=False,
        stop=None,
        random_state=None,
    ):
        self.centers = centers
        self.kernel = kernel
        self.width = width
        self.max_centers = max_centers
        self.ridge = ridge
        self.tol = tol
        self.degree = degree
        self.standardize = standardize
        self.stop = stop
        self.random_state = random_state

    def _native_args(self):
        return dict(
            centers=self.centers,
            kernel=self.kernel,
            width=None if self.width is None else float(self.width),
            max_centers=None if self.max_centers is None else int(self.max_centers),
            ridge=float(self.ridge),
            tol=None if self.tol is None else float(self.tol),
            degree=None if self.degree is None else int(self.degree),
            standardize=bool(self.standardize),
            stop=self.stop,
            seed=_seed(self.random_state),
        )

    def fit(self, X, y):
        """Fit on X (n_samples, n_features) and y (n_samples,) or (n_samples, n_outputs)."""
        with refusals():
            X, y = validate_data(
                self, X, y, y_numeric=True, multi_output=True, dtype=np.float64, ensure_min_samples=2
            )
            self._y_1d = y.ndim == 1
            Y = np.asarray(y, dtype=np.float64).reshape(len(y), -1)
            model = _native.fit_rbf(X, Y, self._native_args())
        self._model = model
        self._fitted_attributes()
        return self

    def _fitted_attributes(self):
        m = self._model
        weights = m.weights.T
        bias = m.bias if m.bias is not None else np.zeros(m.n_outputs)
        self.centers_ = m.centres
        self.coef_ = weights[0] if self._y_1d else weights
        self.intercept_ = float(bias[0]) if self._y_1d else bias
        self.width_ = m.widths
        picks = m.picks
        self.err_ = None if picks is None else np.array([p[1] for p in picks])
        self.condition_ = m.condition

    def predict(self, X):
        """Predictions for X: (n_samples,), or (n_samples, n_outputs) for a 2-D y."""
        check_is_fitted(self)
        with refusals():
            X = validate_data(self, X, reset=False, dtype=np.float64)
            out = self._model.predict(X)
        return out[:, 0] if self._y_1d else out

    def save(self, path, target="y"):
        """Write the ``rbf`` command's model file (``rbf predict --model path``)."""
        check_is_fitted(self)
        if not self._y_1d:
            raise Error(
                f"the rbf command's model file has one target, this model {self._model.n_outputs}: "
                "fit one RBFRegressor per column of y to save each (nothing was written)"
            )
        names = getattr(self, "feature_names_in_", None)
        inputs = [str(n) for n in names] if names is not None else [f"x{i}" for i in range(self.n_features_in_)]
        self._model.save(str(path), inputs, target, "(python)")

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.target_tags.multi_output = True
        return tags
