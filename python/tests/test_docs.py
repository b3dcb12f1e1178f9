"""docs/python.md's Python blocks run, in order, in one namespace, from a folder
that sees the repository's data (`peers/`) and keeps what they write; each block
followed by a ```text block must print exactly that text."""

import contextlib
import io
import re
import warnings

import pytest

from conftest import REPO

BLOCK = re.compile(r"```python\n(.*?)```(?:\s*```text\n(.*?)```)?", re.S)


def blocks():
    return [(code, expected) for code, expected in BLOCK.findall((REPO / "docs" / "python.md").read_text())]


def test_docs_python_blocks_print_what_the_docs_say(tmp_path, monkeypatch):
    found = blocks()
    assert len(found) >= 5 and sum(1 for _, e in found if e) >= 4
    (tmp_path / "peers").symlink_to(REPO / "peers")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for i, (code, expected) in enumerate(found):
        out = io.StringIO()
        with contextlib.redirect_stdout(out), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            exec(compile(code, f"docs/python.md block {i + 1}", "exec"), namespace)
        if expected:
            assert out.getvalue() == expected, f"block {i + 1} printed:\n{out.getvalue()}"
    # the model file block wrote what `rbf predict` reads
    assert (tmp_path / "sunspots-model.json").read_text().startswith("{")
    # and the loop's block the model file `dtg-vib compensate --model` reads
    import rbf_dtg

    saved = rbf_dtg.Model.load(tmp_path / "demo-model.json")
    assert saved.to_json() == namespace["model"].to_json()
    # and the report's block the command's page, its figures SVG files
    figures = namespace["report"].figures
    assert figures and all((tmp_path / f).read_text().startswith("<svg") for f in figures)
    assert '<img src="fit_all_channels.png"' in (tmp_path / "demo-report/index.html").read_text()


def test_docs_refusals_write_nothing(tmp_path):
    import numpy as np

    import rbf_dtg

    X = np.random.default_rng(1).uniform(size=(60, 2))
    est = rbf_dtg.RBFRegressor(max_centers=5).fit(X, np.column_stack([X[:, 0], X[:, 1]]))
    with pytest.raises(rbf_dtg.Error, match="nothing was written"):
        est.save(tmp_path / "m.json")
    assert not list(tmp_path.iterdir())
