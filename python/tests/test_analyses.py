"""The record's analyses and the report from Python (issue 36 §3): ``residues``,
``allan`` and ``model.report`` give the `dtg-vib` command's numbers and files on
the same record and model; ``plot_allan``; the notebook views; bad input refused
with the command's message and nothing written."""

import json
import os
import re
import sys
import tempfile

import numpy as np
import pandas as pd
import pytest

import rbf_dtg

from conftest import run


@pytest.fixture(scope="module")
def cli(tmp_path_factory, dtg_vib):
    """The demo record and the command's model of it, and what the command's
    residues, allan and report give on them."""
    d = tmp_path_factory.mktemp("cli")
    record, model = d / "sim/record.csv", d / "m.json"
    run([dtg_vib, "simulate", "--builtin", "demo", "--out", d / "sim", "--duration", "60"])
    run([dtg_vib, "fit", "--data", record, "--calib", d / "sim/calibration.json", "--out", model, "--quiet"])
    out = {}
    for name, extra in [("with", ["--model", model]), ("without", [])]:
        r = run([dtg_vib, "residues", "--data", record, "--out", d / f"residues-{name}.csv", "--json", "--quiet", *extra])
        a = run([dtg_vib, "allan", "--data", record, "--json", "--quiet", *extra])
        out[name] = (pd.read_csv(d / f"residues-{name}.csv"), json.loads(r.stdout), json.loads(a.stdout))
    run([dtg_vib, "report", "--model", model, "--data", record, "--out", d / "report", "--quiet"])
    return d, record, rbf_dtg.Model.load(model), out


def same_json(ours, theirs, where="", rtol=1e-9):
    """Equal structure, strings and counts; floats within rtol."""
    if isinstance(theirs, dict):
        assert ours.keys() == theirs.keys(), where
        for k in theirs:
            same_json(ours[k], theirs[k], f"{where}.{k}", rtol)
    elif isinstance(theirs, list):
        assert len(ours) == len(theirs), where
        for i, (a, b) in enumerate(zip(ours, theirs)):
            same_json(a, b, f"{where}[{i}]", rtol)
    elif isinstance(theirs, float) and not isinstance(ours, bool):
        np.testing.assert_allclose(ours, theirs, rtol=rtol, atol=0, err_msg=where)
    else:
        assert ours == theirs, where


@pytest.mark.parametrize("with_model", [True, False], ids=["model", "no model"])
def test_residues_are_the_commands(cli, with_model):
    d, record, model, out = cli
    csv, obj, _ = out["with" if with_model else "without"]
    frame = model.residues(record) if with_model else rbf_dtg.residues(pd.read_csv(record))
    assert list(frame.columns) == list(csv.columns)
    assert list(frame.columns[:7]) == ["t", "K0", "K1", "K2", "K3", "K4", "K5"]
    assert ("K0_out" in frame.columns) == with_model
    np.testing.assert_allclose(frame.to_numpy(), csv.to_numpy(), rtol=1e-9, atol=0)
    same_json(frame.attrs["json"], obj)
    # the rms the object states is the frame's
    rms = np.sqrt(np.mean(frame.K3.to_numpy() ** 2))
    np.testing.assert_allclose(rms, obj["residues"][3]["rms_before_deg_h"], rtol=1e-12)
    assert obj["fdi"]["before"]["tests"] == len(frame)


@pytest.mark.parametrize("with_model", [True, False], ids=["model", "no model"])
def test_allan_is_the_commands(cli, with_model):
    d, record, model, out = cli
    _, _, obj = out["with" if with_model else "without"]
    frame = rbf_dtg.allan(pd.read_csv(record), model=model if with_model else None)
    same_json(frame.attrs["json"], dict(obj, segment="DataFrame"))  # the segment named as the caller names it
    names = [s["channel"] for s in obj["channels"]] + [s["residue"] for s in obj["residues"]]
    assert list(dict.fromkeys(frame.series)) == names == ["X", "X1", "Y", "Y1", "Z", "Z1", "K0", "K1", "K2", "K3", "K4", "K5"]
    y1 = frame[frame.series == "Y1"]
    s = obj["channels"][3]
    np.testing.assert_allclose(y1.tau_s, s["tau_s"], rtol=1e-9, atol=0)
    np.testing.assert_allclose(y1.adev_before_deg_h, s["adev_before"], rtol=1e-9, atol=0)
    np.testing.assert_allclose(y1.low_before_deg_h, s["adev_before_detail"]["low"], rtol=1e-9, atol=0)
    np.testing.assert_allclose(y1.high_before_deg_h, s["adev_before_detail"]["high"], rtol=1e-9, atol=0)
    if with_model:
        np.testing.assert_allclose(y1.adev_after_deg_h, s["adev_after"], rtol=1e-9, atol=0)
        np.testing.assert_allclose(y1.high_after_deg_h, s["adev_after_detail"]["high"], rtol=1e-9, atol=0)
        assert (y1.low_after_deg_h < y1.adev_after_deg_h).all() and (y1.adev_after_deg_h < y1.high_after_deg_h).all()
    else:
        assert y1.adev_after_deg_h.isna().all()
    if not with_model:  # another confidence, the command's --confidence: wider intervals
        wide = rbf_dtg.allan(record, confidence=0.95)
        assert wide.attrs["json"]["confidence"] == 0.95
        assert (wide.high_before_deg_h > frame.high_before_deg_h).all()
        assert (wide.low_before_deg_h < frame.low_before_deg_h).all()


def _page_without_provenance(path):
    """The page's text less what names the call: the provenance table and the
    record's and model's names."""
    html = path.read_text()
    html = re.sub(r"<caption>Provenance: what produced this report\.</caption>.*?</table>", "", html, flags=re.S)
    return html


def test_report_writes_the_commands_files(cli, tmp_path):
    d, record, model, _ = cli
    rep = model.report(record, tmp_path / "py")
    theirs = sorted(p.name for p in (d / "report").iterdir())
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == theirs
    figures = [n for n in theirs if n.endswith((".svg", ".png"))]
    assert len(figures) >= 20
    for n in figures:  # every figure, byte for byte
        assert (tmp_path / "py" / n).read_bytes() == (d / "report" / n).read_bytes(), n
    # the page, but for its provenance (the call, the date; the model handed over as model.json)
    ours = _page_without_provenance(tmp_path / "py/index.html").replace("model.json", "m.json")
    assert ours == _page_without_provenance(d / "report/index.html")
    html = (tmp_path / "py/index.html").read_text()
    assert "model.report(" in html and "rbf_dtg-" not in html
    # the numbers the command prints
    assert list(rep.residues.residue) == ["K0", "K1", "K2", "K3", "K4", "K5"]
    assert (rep.residues.rms_after < rep.residues.rms_before).all()
    assert rep.fdi[0].startswith("fault detection, as logged: ")
    # in a notebook: every figure inline as SVG
    assert [os.path.basename(f) for f in rep.figures][:1] == ["fit_all_channels.svg"]
    shown = rep._repr_html_()
    assert shown.count("<svg") == len(rep.figures) == len([n for n in theirs if n.endswith(".svg")])


def test_report_of_a_dataframe_names_it_and_takes_a_baseline(cli, tmp_path):
    d, record, model, _ = cli
    frame = pd.read_csv(record)
    frame.attrs["name"] = "bench-run"
    rep = model.report(frame, tmp_path / "out", baseline=model)
    html = (tmp_path / "out/index.html").read_text()
    assert "Record bench-run (" in html and "rbf_dtg-" not in html
    assert list(rep.against_baseline.channel) == ["X", "X1", "Y", "Y1", "Z", "Z1"]
    np.testing.assert_array_equal(rep.against_baseline.val_rms, rep.against_baseline.val_rms_baseline)


def test_model_shows_a_compact_summary(cli):
    _, _, model, _ = cli
    html = model._repr_html_()
    assert "validation rms (deg/h)" in html and html.count("<tr") == 1 + 6
    v = model.channels.set_index("channel").val_rms
    assert f"{v['Y1']:.4f}" in html


def test_plot_allan_without_matplotlib_says_how_to_get_it(cli, monkeypatch):
    _, record, _, _ = cli
    frame = rbf_dtg.allan(record)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    with pytest.raises(ImportError, match=r"plot_allan draws with matplotlib, which is not installed: python -m pip install matplotlib"):
        rbf_dtg.plot_allan(frame)


def test_plot_allan_draws_log_log_in_deg_h(cli):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    _, record, model, _ = cli
    frame = model.allan(record)
    ax = rbf_dtg.plot_allan(frame, series=["Y1", "K3"])
    assert ax.get_xscale() == ax.get_yscale() == "log"
    assert ax.get_ylabel() == "Allan deviation (deg/h)" and ax.get_xlabel() == "τ (s)"
    assert [line.get_label() for line in ax.get_lines()] == ["Y1 before", "Y1 after", "K3 before", "K3 after"]
    np.testing.assert_array_equal(ax.get_lines()[1].get_ydata(), frame[frame.series == "Y1"].adev_after_deg_h)
    with pytest.raises(rbf_dtg.Error, match="no series W9"):
        rbf_dtg.plot_allan(frame, series="W9")


def staged():
    return {p for p in os.listdir(tempfile.gettempdir()) if p.startswith("rbf_dtg-")}


@pytest.mark.parametrize("case", ["residues missing column", "residues three gyros", "allan wrong unit",
                                  "allan missing column", "report missing column", "report over its record"])
def test_bad_input_raises_the_commands_message_and_writes_nothing(cli, tmp_path, monkeypatch, case):
    d, record, model, _ = cli
    monkeypatch.chdir(tmp_path)
    before = staged()
    short = pd.read_csv(record).iloc[:700]
    no_y1 = short.drop(columns="Y1")
    missing = "DataFrame:1: no column 'Y1' (gyro[3].name in {}); the header has: t, X, X1, Y, Z, Z1, ax, ay, az, temp"
    out = tmp_path / "out"
    if case == "residues missing column":
        call, message = lambda: model.residues(no_y1), missing.format(f"the unit stored in {d / 'm.json'}")
    elif case == "residues three gyros":
        call, message = (lambda: rbf_dtg.residues(short, unit="triad"),
                         "the unit 'triad: three orthogonal rate gyros (MEMS IMU)' (units/triad.toml) has 3 gyros: nothing is redundant, so it has no parity residue")
    elif case == "allan wrong unit":
        call, message = (lambda: rbf_dtg.allan(short, unit="tetr"),
                         "--unit tetr: unknown unit 'tetr' (built-in: paper, triad, tetra, dual-triad; or give a FILE.toml)")
    elif case == "allan missing column":
        call, message = lambda: rbf_dtg.allan(no_y1), missing.format("units/paper.toml")
    elif case == "report missing column":
        call, message = lambda: model.report(no_y1, out), missing.format(f"the unit stored in {d / 'm.json'}")
    else:
        out.mkdir()
        short.to_csv(out / "index.html", index=False)
        call, message = (lambda: model.report(out / "index.html", out),
                         f"out_dir {out / 'index.html'} is the same file as record {out / 'index.html'}: writing it would destroy the input; give out_dir another path")
    with pytest.raises(rbf_dtg.Error) as e:
        call()
    assert str(e.value).startswith(message), str(e.value)
    assert "\n" not in str(e.value) and "rbf_dtg-" not in str(e.value)
    written = sorted(p.name for p in tmp_path.rglob("*"))
    assert written == (["index.html", "out"] if case == "report over its record" else []), written
    assert staged() == before


def test_plot_measured_vs_predicted_draws_the_diagnosis_series(cli):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    _, record, model, _ = cli
    diagnosis = model.diagnose(record)
    ax = diagnosis.plot_measured_vs_predicted("Y1")
    t, measured, predicted = diagnosis.series["Y1"]
    assert [line.get_label() for line in ax.get_lines()] == ["measured", "predicted"]
    np.testing.assert_array_equal(ax.get_lines()[1].get_ydata(), predicted)
    assert ax.get_ylabel() == "Y1 (deg/h)"
