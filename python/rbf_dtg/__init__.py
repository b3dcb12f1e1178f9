"""rbf_dtg: the rbf-dtg Rust workspace from Python.

- :class:`RBFRegressor`: the RBF library (OLS/ERR, k-means or all-points centres,
  QR weights) as a scikit-learn estimator; on the same data and settings it gives
  the ``rbf fit`` command's model.
- The identification loop on DataFrames, with the ``dtg-vib`` command's names,
  flags and files: :class:`Unit`, :func:`read_record`, :func:`simulate`,
  :func:`fit` (a :class:`Model`: ``diagnose``, ``compensate``, ``save``,
  :meth:`Model.load`), :func:`explain`.
- :class:`Error`: every refusal of the package (a ``ValueError``), with the
  command line's one-line message.

Long calls run without the GIL and stop on Ctrl-C between their steps.
"""

from ._native import Error, __version__
from .estimator import RBFRegressor
from .loop import Calibration, Diagnosis, Model, Unit, explain, fit, read_record, simulate

__all__ = [
    "Calibration",
    "Diagnosis",
    "Error",
    "Model",
    "RBFRegressor",
    "Unit",
    "__version__",
    "explain",
    "fit",
    "read_record",
    "simulate",
]
