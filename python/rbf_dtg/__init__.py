"""rbf_dtg: the rbf-dtg Rust workspace from Python.

- :class:`RBFRegressor`: the RBF library (OLS/ERR, k-means or all-points centres,
  QR weights) as a scikit-learn estimator; on the same data and settings it gives
  the ``rbf fit`` command's model.
- The identification loop on DataFrames, with the ``dtg-vib`` command's names,
  flags and files: :class:`Unit`, :func:`read_record`, :func:`simulate`,
  :func:`fit` (a :class:`Model`: ``diagnose``, ``check``, ``compensate``,
  ``residues``, ``allan``, ``report``, ``save``, :meth:`Model.load`),
  :func:`explain`, :func:`residues`, :func:`allan` and :func:`plot_allan`.
- :class:`Error`: every refusal of the package (a ``ValueError``), with the
  command line's one-line message.

Long calls run without the GIL and stop on Ctrl-C between their steps.
"""

from ._native import Error, __version__
from .estimator import RBFRegressor
from .loop import (Calibration, Diagnosis, Model, Report, Unit, allan, explain, fit, plot_allan, read_record,
                   residues, simulate)

__all__ = [
    "Calibration",
    "Diagnosis",
    "Error",
    "Model",
    "RBFRegressor",
    "Report",
    "Unit",
    "__version__",
    "allan",
    "explain",
    "fit",
    "plot_allan",
    "read_record",
    "residues",
    "simulate",
]
