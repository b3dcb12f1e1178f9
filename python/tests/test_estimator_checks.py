"""scikit-learn's own conformance suite on RBFRegressor (issue 36 §2)."""

import pytest
from sklearn.utils.estimator_checks import check_estimator

from rbf_dtg import RBFRegressor


@pytest.mark.parametrize(
    "params",
    [{}, {"centers": "kmeans"}, {"centers": "all", "ridge": 1e-8}, {"stop": "press"}],
    ids=["defaults", "kmeans", "all", "press"],
)
def test_check_estimator_passes_every_check(params):
    # on_fail=None: every check's outcome, rather than a stop at the first failure
    results = check_estimator(RBFRegressor(**params), on_fail=None)
    failed = [f"{r['check_name']}: {r['exception']!r}" for r in results if r["status"] == "failed"]
    passed = [r for r in results if r["status"] == "passed"]
    assert len(passed) > 40, f"check_estimator ran only {len(passed)} checks"
    assert not failed, "\n".join(failed)
