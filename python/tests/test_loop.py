"""The identification loop on DataFrames (issue 36 §3): the demo's loop in Python,
the same numbers as the `dtg-vib` command on the same record, a tetra unit, and
bad input refused with the command's message and nothing written."""

import json
import os
import tempfile

import numpy as np
import pandas as pd
import pytest

import rbf_dtg

from conftest import run


@pytest.fixture(scope="module")
def demo():
    """The demo record, its calibration and truth (the built-in scenario, seeded)."""
    return rbf_dtg.simulate(builtin="demo")


@pytest.fixture(scope="module")
def base(demo):
    record, calibration, _ = demo
    return rbf_dtg.fit(record, calibration=calibration)


@pytest.fixture(scope="module")
def diagnosis(base, demo):
    return base.diagnose(demo.record)


@pytest.fixture(scope="module")
def cli(tmp_path_factory, dtg_vib):
    """The command's loop on the same record: simulate, fit, diagnose, compensate."""
    d = tmp_path_factory.mktemp("cli")
    run([dtg_vib, "simulate", "--builtin", "demo", "--out", d / "sim"])
    run([dtg_vib, "fit", "--data", d / "sim/record.csv", "--calib", d / "sim/calibration.json",
         "--out", d / "base.json", "--quiet"])
    diag = run([dtg_vib, "diagnose", "--model", d / "base.json", "--data", d / "sim/record.csv", "--json", "--quiet"])
    run([dtg_vib, "compensate", "--model", d / "base.json", "--data", d / "sim/record.csv",
         "--out", d / "comp.csv", "--quiet"])
    return d, json.loads(diag.stdout)


def same(a, b, rtol=1e-9):
    np.testing.assert_allclose(a, b, rtol=rtol, atol=0)


def test_simulate_gives_the_commands_record_and_calibration(demo, cli):
    d, _ = cli
    record, calibration, truth = demo
    from_file = pd.read_csv(d / "sim/record.csv")
    assert list(record.columns) == list(from_file.columns) == ["t", "X", "X1", "Y", "Y1", "Z", "Z1", "ax", "ay", "az", "temp"]
    np.testing.assert_array_equal(record.to_numpy(), from_file.to_numpy())
    assert calibration.to_dict() == json.loads((d / "sim/calibration.json").read_text())
    assert truth == json.loads((d / "sim/truth.json").read_text())


def test_fit_gives_the_commands_model(base, cli):
    d, _ = cli
    ours = json.loads(base.to_json())["model"]
    theirs = json.loads((d / "base.json").read_text())["model"]
    assert ours.keys() == theirs.keys()
    for a, b in zip(ours["channels"], theirs["channels"]):
        assert a["channel"] == b["channel"]
        assert len(a["centres"]) == len(b["centres"]) if "centres" in a else True
    summary = base.summary()
    assert [c["channel"] for c in summary["channels"]] == ["X", "X1", "Y", "Y1", "Z", "Z1"]
    cli_summary = rbf_dtg.Model.load(d / "base.json").summary()
    for a, b in zip(summary["channels"], cli_summary["channels"]):
        assert a["n_centers"] == b["n_centers"]
        same([a["train_rms"], a["val_rms"], a["bias"], a["width"]], [b["train_rms"], b["val_rms"], b["bias"], b["width"]])


def test_diagnose_gives_the_commands_findings(diagnosis, cli):
    _, theirs = cli
    f = diagnosis.findings
    rows = [(c["channel"], k) for c in theirs["channels"] for k in c["candidates"]]
    assert len(f) == len(rows) > 0
    for (channel, k), row in zip(rows, f.itertuples()):
        assert (row.channel, row.effect) == (channel, k["effect"])
        same([row.coefficient, row.standard_error, row.ci95_low, row.ci95_high],
             [k["coef"], k["coef_se"], k["coef_ci95"][0], k["coef_ci95"][1]])
    assert diagnosis.suggested == {c["channel"]: c["suggested"] for c in theirs["channels"]}


def test_compensate_gives_the_commands_csv(base, demo, cli):
    d, _ = cli
    ours = base.compensate(demo.record)
    theirs = pd.read_csv(d / "comp.csv")
    assert list(ours.columns) == list(theirs.columns)
    assert len(ours) == len(theirs) == len(demo.record) - 49
    same(ours.to_numpy(), theirs.to_numpy(), rtol=1e-12)


def test_model_files_are_the_commands(base, demo, cli, tmp_path, dtg_vib):
    d, _ = cli
    base.save(tmp_path / "py.json")
    # the command reads the package's model file ...
    run([dtg_vib, "compensate", "--model", tmp_path / "py.json", "--data", d / "sim/record.csv",
         "--out", tmp_path / "comp.csv", "--quiet"])
    same(pd.read_csv(tmp_path / "comp.csv").to_numpy(), pd.read_csv(d / "comp.csv").to_numpy(), rtol=1e-12)
    # ... and the package the command's, to the same compensation
    cli_model = rbf_dtg.Model.load(d / "base.json")
    np.testing.assert_array_equal(cli_model.compensate(demo.record).to_numpy(), base.compensate(demo.record).to_numpy())


def test_a_pickled_model_compensates_bit_identically(base, demo):
    import pickle

    back = pickle.loads(pickle.dumps(base))
    assert back.to_json() == base.to_json()
    np.testing.assert_array_equal(back.compensate(demo.record).to_numpy(), base.compensate(demo.record).to_numpy())


def test_the_demo_loop_in_python(demo, base, diagnosis):
    """simulate, fit, diagnose names Y1 col:temp, refit with it: Y1's error falls."""
    record, calibration, truth = demo
    assert diagnosis.suggested["Y1"] == ["col:temp"]
    assert all(not s for ch, s in diagnosis.suggested.items() if ch != "Y1")
    row = diagnosis.findings.query("channel == 'Y1' and effect == 'col:temp'").iloc[0]
    assert row.suggested and row.ci95_low < 0.6 < row.ci95_high  # the hidden 0.6 deg/h/°C
    refit = rbf_dtg.fit(record, calibration=calibration, add_effects={"Y1": ["col:temp"]})
    before = {c["channel"]: c["val_rms"] for c in base.summary()["channels"]}
    after = {c["channel"]: c["val_rms"] for c in refit.summary()["channels"]}
    assert after["Y1"] < 0.6 * before["Y1"], (before, after)
    e = refit.effects
    assert list(e.channel) == ["Y1"] and list(e.effect) == ["col:temp"]
    assert e.ci95_low[0] < 0.6 < e.ci95_high[0]


def test_a_tetra_unit(tmp_path, dtg_vib):
    tetra = rbf_dtg.Unit.builtin("tetra")
    assert tetra.gyros == ["g1", "g2", "g3", "g4"] and tetra.residues
    with pytest.warns(UserWarning, match="has no DTG channel Y1"):  # the demo hides Y1's, which tetra lacks
        record, calibration, truth = rbf_dtg.simulate(builtin="demo", unit=tetra, duration=40)
    assert list(record.columns[:5]) == ["t", "g1", "g2", "g3", "g4"]
    model = rbf_dtg.fit(record, unit=tetra, calibration=calibration, max_centres=20, input="raw", smoother="none")
    assert model.unit.file == "units/tetra.toml" and model.unit.arg == "tetra"
    comp = model.compensate(record)
    assert list(comp.columns) == list(record.columns)
    # the command on the same files gives the same compensation
    record.to_csv(tmp_path / "r.csv", index=False)
    calibration.save(tmp_path / "c.json")
    model.save(tmp_path / "m.json")
    run([dtg_vib, "compensate", "--model", tmp_path / "m.json", "--data", tmp_path / "r.csv",
         "--out", tmp_path / "comp.csv", "--quiet"])
    same(comp.to_numpy(), pd.read_csv(tmp_path / "comp.csv").to_numpy(), rtol=1e-12)


def staged():
    return {p for p in os.listdir(tempfile.gettempdir()) if p.startswith("rbf_dtg-")}


@pytest.mark.parametrize("case", ["missing column", "NaN", "wrong unit"])
def test_bad_input_raises_the_commands_message_and_writes_nothing(demo, tmp_path, monkeypatch, case):
    record, calibration, _ = demo
    monkeypatch.chdir(tmp_path)
    before = staged()
    short = record.iloc[:600].copy()
    if case == "missing column":
        call, message = (lambda: rbf_dtg.fit(short.drop(columns="Y1"), calibration=calibration),
                         "DataFrame:1: no column 'Y1' (gyro[3].name in units/paper.toml); the header has: t, X, X1, Y, Z, Z1, ax, ay, az, temp")
    elif case == "NaN":
        short.loc[7, "az"] = np.nan
        call, message = (lambda: rbf_dtg.fit(short, calibration=calibration),
                         "DataFrame:9:10: column 'az': 'NaN' is not finite")
    else:
        call, message = (lambda: rbf_dtg.fit(short, unit="tetr"),
                         "--unit tetr: unknown unit 'tetr' (built-in: paper, triad, tetra, dual-triad; or give a FILE.toml)")
    with pytest.raises(rbf_dtg.Error) as e:
        call()
    assert str(e.value).startswith(message), str(e.value)
    assert "\n" not in str(e.value)
    assert list(tmp_path.iterdir()) == [] and staged() == before


def test_read_record_reads_a_log_as_the_command_does():
    from conftest import REPO

    csv = REPO / "data/realdata/xio_fusion_handheld.csv"
    frame = rbf_dtg.read_record(csv, unit="triad")
    raw = pd.read_csv(csv)
    assert list(frame.columns) == list(raw.columns) == ["t", "gx", "gy", "gz", "ax", "ay", "az"]
    # to deg/h and g and back to the unit's deg/s and m/s²: within rounding
    same(frame.to_numpy(), raw.to_numpy(), rtol=1e-14)
    with pytest.raises(rbf_dtg.Error, match="the log has the columns of built-in unit triad: add --unit triad"):
        rbf_dtg.read_record(csv)
    ulg = REPO.parent / "shared/realdata/ulog/sample_log_small.ulg"
    if ulg.exists():  # not in the tree (see crates/dtg-vib/tests/real_logs_cli.rs)
        from_ulog = rbf_dtg.read_record(ulg, unit="triad")
        from_csv = rbf_dtg.read_record(REPO / "data/realdata/px4_cubeorange_vtol_ground.csv", unit="triad")
        sensors = ["t", "gx", "gy", "gz", "ax", "ay", "az"]  # the CSV has an extra column
        assert list(from_ulog.columns) == sensors and len(from_ulog) == len(from_csv)
        np.testing.assert_allclose(from_ulog.to_numpy(), from_csv[sensors].to_numpy(), rtol=1e-5, atol=1e-6)


def test_explain_returns_the_final_model_and_its_rounds(demo):
    record, calibration, _ = demo
    result = rbf_dtg.explain(record, calibration=calibration, max_rounds=2)
    model, rounds = result
    assert len(rounds) == 2 and rounds[0]["added"] == []
    added = rounds[1]["added"]
    assert [(a["channel"], a["effect"]) for a in added] == [("Y1", "col:temp")]
    assert added[0]["ci95"][0] < 0.6 < added[0]["ci95"][1]
    e = model.effects
    assert list(zip(e.channel, e.effect)) == [("Y1", "col:temp")]
    assert isinstance(result.converged, bool)


def test_check_gives_the_commands_numbers(base, demo, cli, dtg_vib):
    d, _ = cli
    theirs = json.loads(run([dtg_vib, "check", "--model", d / "base.json", "--data", d / "sim/record.csv",
                             "--json", "--quiet"]).stdout)
    channels, residues, ours = base.check(demo.record)
    assert list(channels.channel) == [c["channel"] for c in theirs["channels"]]
    for key in ["rms_before", "rms_after"]:
        same(channels[key].to_numpy(), [c[key] for c in theirs["channels"]])
    assert len(residues) == len(theirs["residues"]) == 6
    with pytest.raises(rbf_dtg.Error, match="outside_threshold"):
        base.check(demo.record, outside_threshold=2.0)
