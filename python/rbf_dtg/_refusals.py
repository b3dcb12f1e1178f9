"""Input refused by scikit-learn's validation is refused as rbf_dtg.Error too, so
that one ``except rbf_dtg.Error`` catches every refusal of the package."""

from contextlib import contextmanager

from sklearn.exceptions import NotFittedError

from ._native import Error


@contextmanager
def refusals():
    try:
        yield
    except (Error, NotFittedError):
        raise
    except ValueError as e:
        raise Error(str(e)) from e
