"""rbf_dtg: the rbf-dtg Rust workspace from Python.

- :class:`RBFRegressor`: the RBF library (OLS/ERR, k-means or all-points centres,
  QR weights) as a scikit-learn estimator; on the same data and settings it gives
  the ``rbf fit`` command's model.
- :class:`Error`: every refusal of the package (a ``ValueError``), with the
  command line's one-line message.

Long calls run without the GIL and stop on Ctrl-C between their steps.
"""

from ._native import Error, __version__
from .estimator import RBFRegressor

__all__ = ["Error", "RBFRegressor", "__version__"]
