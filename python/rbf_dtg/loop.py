"""The identification loop on DataFrames: the ``dtg-vib`` command's names, flags
and files (issue 36 §3).

Every call goes to the command's own library functions (``dtg_vib::recipe``):
a DataFrame is handed over as the log the command would read (its columns, in
their shortest round-trip text, so the bits are the same), a calibration as its
file, and the answers come back as the command's ``--json`` objects and CSV
columns, made into DataFrames here. Nothing of the identification is computed
in Python.
"""

import json
import os
import tempfile
import warnings

import numpy as np
import pandas as pd

from . import _native
from ._native import Error


def _label(frame, default):
    name = frame.attrs.get("name") if hasattr(frame, "attrs") else None
    return str(name) if name else default


def _source(record, default="DataFrame"):
    """A record as the binding takes it: a path, or (label, names, columns)."""
    if isinstance(record, (str, os.PathLike)):
        return os.fspath(record)
    if not isinstance(record, pd.DataFrame):
        raise Error(f"a record is a pandas DataFrame or the path of a log, not {type(record).__name__}")
    label = _label(record, default)
    names, columns = [], []
    for name in record.columns:
        try:
            values = record[name].to_numpy(dtype=np.float64)
        except (TypeError, ValueError):
            raise Error(
                f"{label}: column '{name}' holds {record[name].dtype} values, not numbers: drop it or convert it"
            ) from None
        names.append(str(name))
        columns.append(np.ascontiguousarray(values))
    return (label, names, columns)


def _sources(records):
    """One record or a list of them (the command's repeated --data)."""
    if isinstance(records, (list, tuple)):
        if len(records) == 1:
            return [_source(records[0])]
        return [_source(r, f"DataFrame[{k}]") for k, r in enumerate(records)]
    return [_source(records)]


def _warn(notes):
    for n in notes:
        warnings.warn(n, stacklevel=3)


def _frame(table):
    names, columns = table
    return pd.DataFrame(dict(zip(names, columns)), columns=names)


def _unit_arg(unit):
    if unit is None:
        return None
    if isinstance(unit, Unit):
        return unit.arg
    if isinstance(unit, (str, os.PathLike)):
        return os.fspath(unit)
    raise Error(f"unit: a Unit, a built-in name or a unit file's path, not {type(unit).__name__}")


def _calibration_source(calibration):
    if calibration is None:
        return None
    if isinstance(calibration, Calibration):
        return ("calibration.json", calibration.text)
    if isinstance(calibration, (str, os.PathLike)):
        return os.fspath(calibration)
    raise Error(f"calibration: a Calibration or a calibration file's path, not {type(calibration).__name__}")


def _flags(options):
    """Keyword arguments as the command's flags: ``max_centres=40`` is
    ``--max-centres 40``, ``no_filter=True`` is ``--no-filter``, a list is
    comma-separated; None and False are left out (the command's default)."""
    flags = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            flags.append(flag)
        elif isinstance(value, (list, tuple)):
            flags += [flag, ",".join(str(v) for v in value)]
        else:
            flags += [flag, str(value)]
    return flags


def _pyplot(what):
    """matplotlib's pyplot, or an ImportError saying how to get it."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            f"{what} draws with matplotlib, which is not installed: "
            "python -m pip install matplotlib (or install the package with './python[plot]')"
        ) from e
    return plt


def _native_model(model, what="model"):
    if model is None:
        return None
    if isinstance(model, Model):
        return model._native
    raise Error(f"{what}: a Model (rbf_dtg.fit, rbf_dtg.Model.load), not {type(model).__name__}")


class Unit:
    """A sensor unit, as the command's ``--unit`` names it: a built-in unit
    (``paper``, ``triad``, ``tetra``, ``dual-triad``) or a unit file."""

    def __init__(self, arg, info=None):
        self.arg = arg
        info = _native.unit_info(arg) if info is None else info
        self.name = info["name"]
        self.file = info["file"]
        self.gyros = list(info["gyros"])
        self.accels = list(info["accels"])
        self.residues = list(info["residues"])
        self.columns = dict(info["columns"])

    @classmethod
    def builtin(cls, name):
        """A built-in unit by name."""
        name = str(name)
        if name.endswith(".toml") or "/" in name or "\\" in name:
            raise Error(f"'{name}' is a file name: use Unit.from_file for a unit file")
        return cls(name)

    @classmethod
    def from_file(cls, path):
        """A unit file (TOML, docs/formats.md)."""
        path = os.fspath(path)
        if not (path.endswith(".toml") or "/" in path or "\\" in path):
            path = os.path.join(".", path)
        return cls(path)

    def to_toml(self):
        """The unit written as a unit file."""
        return _native.unit_toml(self.arg)

    @classmethod
    def _of_model(cls, native):
        info = native.unit_info()
        file = info["file"]
        builtin = file.startswith("units/") and file.endswith(".toml") and file.count("/") == 1
        return cls(file[len("units/"):-len(".toml")] if builtin else file, info)

    def __eq__(self, other):
        return isinstance(other, Unit) and self.to_toml() == other.to_toml()

    def __repr__(self):
        return f"Unit('{self.name}': gyros {', '.join(self.gyros)}; accelerometers {', '.join(self.accels)})"

    def _repr_html_(self):
        rows = "".join(f"<tr><th>{k}</th><td>{', '.join(v) or '—'}</td></tr>" for k, v in
                       [("gyros", self.gyros), ("accelerometers", self.accels), ("parity residues", self.residues)])
        return f"<b>unit {self.name}</b> <small>({self.file})</small><table>{rows}</table>"


class Calibration:
    """A ground calibration: the text of its file (either format)."""

    def __init__(self, text):
        self.text = text

    @classmethod
    def load(cls, path):
        with open(path, encoding="utf-8") as f:
            return cls(f.read())

    def to_dict(self):
        return json.loads(self.text)

    def save(self, path):
        _native.write_text(os.fspath(path), self.text)

    def __repr__(self):
        return f"Calibration({len(self.text)} characters of JSON)"


class Simulation(tuple):
    """What ``simulate`` returns: ``record, calibration, truth = simulate(...)``."""

    def __new__(cls, record, calibration, truth, notes):
        self = super().__new__(cls, (record, calibration, truth))
        self.record, self.calibration, self.truth, self.notes = record, calibration, truth, notes
        return self


def read_record(path, unit=None):
    """A log (CSV in the unit's columns, or a PX4 ULog where the unit reads one)
    read as the command reads ``--data``: the unit's columns and units, its
    segments between time gaps one after the other. Notes (gaps, declared units
    the data contradict) are in ``frame.attrs["notes"]``."""
    table, notes = _native.read_record(os.fspath(path), _unit_arg(unit))
    _warn(notes)
    frame = _frame(table)
    frame.attrs["notes"] = notes
    frame.attrs["name"] = os.path.basename(os.fspath(path))
    return frame


def simulate(builtin=None, unit=None, seed=None, duration=None, scenario=None):
    """``dtg-vib simulate``: a vibration test of a built-in scenario (or a
    scenario file) on a unit. Returns ``(record, calibration, truth)``: the
    record as a DataFrame, the ground calibration, the truth as a dict."""
    scenario = None if scenario is None else os.fspath(scenario)
    table, calibration, truth, notes = _native.simulate(builtin, scenario, _unit_arg(unit), seed, duration)
    _warn(notes)
    record = _frame(table)
    return Simulation(record, Calibration(calibration), json.loads(truth), notes)


def fit(record, unit=None, calibration=None, effects=None, add_effects=None, **flags):
    """``dtg-vib fit``: every gyro channel's model fitted on the record (a
    DataFrame or a log's path; a list of them for several records). Every other
    keyword is the command's flag of that name (``causal=True``,
    ``max_centres=40``, ``window_signals="az"``, …) with its default.
    ``add_effects={"Y1": ["col:temp"]}`` is ``--add-effect Y1=col:temp``."""
    args = _flags(dict(unit=_unit_arg(unit), effects=effects, **flags))
    for channel, ids in (add_effects or {}).items():
        for effect_id in [ids] if isinstance(ids, str) else ids:
            args += ["--add-effect", f"{channel}={effect_id}"]
    native, notes = _native.fit(_sources(record), _calibration_source(calibration), args)
    _warn(notes)
    return Model(native)


def explain(record, unit=None, calibration=None, effects=None, add_effects=None, **flags):
    """``dtg-vib explain``: fit, diagnose, add what is suggested, refit, until
    nothing new is suggested. Returns the final :class:`Model` and the rounds
    (the command's ``--json`` rounds, one dict each) and whether the loop
    converged (False: it stopped at ``max_rounds``)."""
    args = _flags(dict(unit=_unit_arg(unit), effects=effects, **flags))
    for channel, ids in (add_effects or {}).items():
        for effect_id in [ids] if isinstance(ids, str) else ids:
            args += ["--add-effect", f"{channel}={effect_id}"]
    native, rounds, converged, notes = _native.explain(_sources(record), _calibration_source(calibration), args)
    _warn(notes)
    return Explanation(Model(native), json.loads(rounds), converged)


class Explanation(tuple):
    """What ``explain`` returns: ``model, rounds = explain(...)``; ``converged``."""

    def __new__(cls, model, rounds, converged):
        self = super().__new__(cls, (model, rounds))
        self.model, self.rounds, self.converged = model, rounds, converged
        return self


def residues(record, unit=None, model=None, fdi_sigma=None, fdi_false_alarm=None):
    """``dtg-vib residues``: the parity residues of every sample (the paper's
    K0..K5, another unit's P0, …; deg/h) as the command's ``--out`` CSV has
    them: ``t``, each residue R as logged and, with a model, ``R_pre``
    (pre-processed), ``R_comp`` (less the prediction) and ``R_out`` (of the
    gyros as ``compensate`` writes them). ``frame.attrs["json"]`` is the
    command's ``--json`` object: each residue's rms, the fault-detection test
    (``fdi_sigma`` deg/h per sample, default read from the record;
    ``fdi_false_alarm`` per sample) and what it found before and after, and
    with a model the residues on its validation rows. A unit of three gyros
    has no residue and is refused."""
    table, text, notes = _native.residues(_source(record), _unit_arg(unit), _native_model(model),
                                          fdi_sigma, fdi_false_alarm)
    _warn(notes)
    frame = _frame(table)
    frame.attrs["json"] = json.loads(text)
    return frame


ALLAN_COLUMNS = ["series", "kind", "tau_s", "adev_before_deg_h", "low_before_deg_h", "high_before_deg_h",
                 "adev_after_deg_h", "low_after_deg_h", "high_after_deg_h"]


def allan(record, unit=None, model=None, confidence=None):
    """``dtg-vib allan``: the overlapping Allan deviation of every gyro channel
    and parity residue of the record's longest segment, before and, with a
    model, after its compensation. One row per series and τ (s): the deviation
    and its interval at ``confidence`` (two-sided, default the command's
    0.683), in deg/h. ``frame.attrs["json"]`` is the command's ``--json``
    object, with the IEEE 952 noise terms of each series."""
    text, notes = _native.allan(_source(record), _unit_arg(unit), _native_model(model), confidence)
    _warn(notes)
    j = json.loads(text)
    rows = []
    for kind, key in (("channel", "channels"), ("residue", "residues")):
        for s in j[key]:
            before, after = s["adev_before_detail"], s.get("adev_after_detail")
            for i, tau in enumerate(s["tau_s"]):
                rows.append([s[kind], kind, tau, s["adev_before"][i], before["low"][i], before["high"][i],
                             s["adev_after"][i] if after else np.nan, after["low"][i] if after else np.nan,
                             after["high"][i] if after else np.nan])
    frame = pd.DataFrame(rows, columns=ALLAN_COLUMNS)
    frame.attrs["json"] = j
    return frame


def plot_allan(frame, series=None, ax=None):
    """The Allan deviation of :func:`allan`'s frame, log-log (deg/h against τ
    in s): each series before (solid) and after (dashed) with its interval
    shaded. ``series``: the names to draw (default every channel). Needs
    matplotlib."""
    plt = _pyplot("plot_allan")
    if series is None:
        series = list(dict.fromkeys(frame.series[frame.kind == "channel"]))
    elif isinstance(series, str):
        series = [series]
    unknown = [s for s in series if s not in set(frame.series)]
    if unknown:
        raise Error(f"plot_allan: no series {', '.join(unknown)}; the frame has {', '.join(dict.fromkeys(frame.series))}")
    ax = ax or plt.subplots(figsize=(7, 5))[1]
    for name in series:
        s = frame[frame.series == name]
        (line,) = ax.loglog(s.tau_s, s.adev_before_deg_h, label=f"{name} before")
        ax.fill_between(s.tau_s, s.low_before_deg_h, s.high_before_deg_h, color=line.get_color(), alpha=0.15, lw=0)
        if s.adev_after_deg_h.notna().any():
            ax.loglog(s.tau_s, s.adev_after_deg_h, "--", color=line.get_color(), label=f"{name} after")
            ax.fill_between(s.tau_s, s.low_after_deg_h, s.high_after_deg_h, color=line.get_color(), alpha=0.1, lw=0)
    ax.set(xlabel="τ (s)", ylabel="Allan deviation (deg/h)", title="Overlapping Allan deviation")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize="small")
    return ax


class Report:
    """What ``model.report`` wrote (``dtg-vib report``): ``index``, the page;
    ``figures``, its figures' SVG files in page order; and the numbers the
    command prints: ``validation`` (each residue's rms before and after on the
    validation rows, deg/h), ``residues`` (on every sample), ``fdi`` (the
    fault-detection lines) and ``against_baseline`` (each channel's
    validation rms under the baseline and this model). In a notebook it
    shows its figures inline as SVG."""

    def __init__(self, index, printed, notes):
        every, fdi, validation, against = printed
        self.index = os.fspath(index)
        self.dir = os.path.dirname(self.index)
        self.notes = notes
        self.residues = pd.DataFrame(every, columns=["residue", "rms_before", "rms_after"])
        self.fdi = list(fdi)
        self.validation = pd.DataFrame(json.loads(validation))
        self.against_baseline = pd.DataFrame(against, columns=["channel", "val_rms_baseline", "val_rms"])

    @property
    def figures(self):
        import re

        with open(self.index, encoding="utf-8") as f:
            html = f.read()
        stems = dict.fromkeys(re.findall(r'<img src="([^"/]+)\.png"', html))
        return [os.path.join(self.dir, f"{s}.svg") for s in stems if os.path.exists(os.path.join(self.dir, f"{s}.svg"))]

    def __repr__(self):
        return f"Report({self.index}: {len(self.figures)} figures)"

    def _repr_html_(self):
        import html

        parts = [f"<b>report</b> <code>{html.escape(self.index)}</code>"]
        for path in self.figures:
            with open(path, encoding="utf-8") as f:
                parts.append(f"<div>{f.read()}</div>")
        return "".join(parts)


class Diagnosis:
    """What a model is missing (``dtg-vib diagnose``): ``findings``, one row per
    channel and candidate effect; ``channels``, one row per channel; ``notes``,
    each channel's plain-language findings (where the model fails); ``json``,
    the command's ``--json`` object."""

    def __init__(self, text, series=None):
        self.json = json.loads(text)
        self.series = series or {}
        rows, channels = [], []
        self.notes = {}
        for c in self.json["channels"]:
            suggested = set(c["suggested"])
            channels.append({
                "channel": c["channel"],
                "validation_rms": c["rms"],
                "fit_percent": c["compare"]["val_fit_percent"],
                "suggested": ", ".join(c["suggested"]),
                "failing": ", ".join(c.get("failing", [])),
            })
            self.notes[c["channel"]] = list(c["findings"])
            for k in c["candidates"]:
                rows.append({
                    "channel": c["channel"],
                    "effect": k["effect"],
                    "coefficient": k["coef"],
                    "standard_error": k["coef_se"],
                    "ci95_low": k["coef_ci95"][0],
                    "ci95_high": k["coef_ci95"][1],
                    "unit": k["unit"],
                    "p": k.get("p_value"),
                    "err": k["err"],
                    "suggested": k["effect"] in suggested,
                    "caveats": "; ".join(k.get("caveats", [])),
                    "description": k["description"],
                })
        columns = ["channel", "effect", "coefficient", "standard_error", "ci95_low", "ci95_high", "unit",
                   "p", "err", "suggested", "caveats", "description"]
        self.findings = pd.DataFrame(rows, columns=columns)
        self.channels = pd.DataFrame(channels, columns=["channel", "validation_rms", "fit_percent", "suggested", "failing"])

    def plot_measured_vs_predicted(self, channel, ax=None):
        """Measured against predicted output of one channel over time (matplotlib)."""
        plt = _pyplot("plot_measured_vs_predicted")

        t, measured, predicted = self.series[channel]
        ax = ax or plt.subplots(figsize=(8, 3))[1]
        ax.plot(t, measured, lw=0.6, label="measured")
        ax.plot(t, predicted, lw=0.8, label="predicted")
        ax.set(xlabel="t (s)", ylabel=f"{channel} (deg/h)", title=f"{channel}: measured and predicted")
        ax.legend()
        return ax

    @property
    def suggested(self):
        """Each channel's suggested effects."""
        return {c["channel"]: list(c["suggested"]) for c in self.json["channels"]}

    def __repr__(self):
        lines = [f"{r.channel}: validation rms {r.validation_rms:.4f} deg/h, suggested: {r.suggested or 'nothing'}"
                 for r in self.channels.itertuples()]
        return "\n".join(lines)

    def _repr_html_(self):
        notes = "".join(f"<li><b>{ch}</b>: {'; '.join(n)}</li>" for ch, n in self.notes.items() if n)
        return (self.channels.to_html(index=False) + (f"<ul>{notes}</ul>" if notes else "")
                + self.findings[self.findings.suggested | (self.findings.p.fillna(1) < 0.05)].to_html(index=False))


class Model:
    """A fitted model of every gyro channel (the command's model file)."""

    def __init__(self, native):
        self._native = native

    @classmethod
    def load(cls, path):
        """A model file of ``dtg-vib fit --out``."""
        return cls(_native.Model.load(os.fspath(path)))

    def save(self, path):
        """Writes the model file ``dtg-vib compensate --model`` reads, atomically."""
        self._native.save(os.fspath(path))

    @classmethod
    def _from_json(cls, text):
        with tempfile.TemporaryDirectory(prefix="rbf_dtg-") as d:
            path = os.path.join(d, "model.json")
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            return cls.load(path)

    def __reduce__(self):
        # pickled as its model file, which compensates bit-identically once read back
        return (Model._from_json, (self.to_json(),))

    @property
    def unit(self):
        """The unit the model was fitted with (a model stores it)."""
        return Unit._of_model(self._native)

    def summary(self):
        """``dtg-vib fit --json``'s object of the model: each channel's centres,
        scores and effect coefficients, the split, the input and smoother."""
        return json.loads(self._native.summary_json())

    @property
    def channels(self):
        """One row per channel: centres, training and validation rms (deg/h), fit %."""
        rows = [{"channel": c["channel"], "centres": c["n_centers"], "train_rms": c["train_rms"],
                 "val_rms": c["val_rms"], "val_fit_percent": c["val_fit_percent"],
                 "effects": ", ".join(c["effects"])} for c in self.summary()["channels"]]
        return pd.DataFrame(rows, columns=["channel", "centres", "train_rms", "val_rms", "val_fit_percent", "effects"])

    @property
    def effects(self):
        """Each channel's effects and their coefficients: one row per channel and
        effect, with the standard error and 95 % interval."""
        rows = []
        for c in self.summary()["channels"]:
            for effect, k in c["effect_coefficients"].items():
                ci = k.get("ci95") or [np.nan, np.nan]
                rows.append({"channel": c["channel"], "effect": effect, "coefficient": k["value"],
                             "standard_error": k.get("se", np.nan), "ci95_low": ci[0], "ci95_high": ci[1],
                             "unit": k["unit"]})
        return pd.DataFrame(rows, columns=["channel", "effect", "coefficient", "standard_error", "ci95_low",
                                           "ci95_high", "unit"])

    def diagnose(self, record, alpha=None, min_gain=None):
        """``dtg-vib diagnose``: what the model is missing on its record(s)."""
        text, series = self._native.diagnose(_sources(record), _flags(dict(alpha=alpha, min_gain=min_gain)))
        return Diagnosis(text, series)

    def check(self, record, outside_threshold=None):
        """``dtg-vib check --json``: does the model hold on a record it was not
        fitted on? Returns (channels, residues, the command's whole object):
        per channel the rms before and after (deg/h) and on the windows inside and
        outside the training range; per parity residue before and after."""
        c = json.loads(self._native.check(_source(record), outside_threshold))
        for w in ("warning", "note"):
            if c.get(w):
                warnings.warn(c[w], stacklevel=2)
        return pd.DataFrame(c["channels"]), pd.DataFrame(c["residues"]), c

    def compensate(self, record):
        """``dtg-vib compensate``: the record with the model's prediction removed,
        in the unit's names and units (each segment from its first full window)."""
        table, notes, _ = self._native.compensate(_source(record))
        _warn(notes)
        return _frame(table)

    def residues(self, record, fdi_sigma=None, fdi_false_alarm=None):
        """``dtg-vib residues --model``: :func:`residues` with this model."""
        return residues(record, model=self, fdi_sigma=fdi_sigma, fdi_false_alarm=fdi_false_alarm)

    def allan(self, record, confidence=None):
        """``dtg-vib allan --model``: :func:`allan` with this model."""
        return allan(record, model=self, confidence=confidence)

    def report(self, record, out_dir, baseline=None):
        """``dtg-vib report``: writes the figures and index.html of the model on
        the record into ``out_dir`` (made if missing; each file atomically, never
        over an input), against ``baseline`` (a model of the same unit) where
        given. Returns a :class:`Report`."""
        label = _label(record, "DataFrame") if isinstance(record, pd.DataFrame) else os.fspath(record)
        command = f"rbf_dtg {_native.__version__}: model.report({label}, {os.fspath(out_dir)!r})"
        index, printed, notes = self._native.report(_source(record), os.fspath(out_dir), command,
                                                    _native_model(baseline, "baseline"))
        _warn(notes)
        return Report(index, printed, notes)

    def to_json(self):
        """The model file's text."""
        return self._native.to_json()

    def __repr__(self):
        e = self.effects
        per = ", ".join(f"{ch}: {', '.join(g.effect)}" for ch, g in e.groupby("channel", sort=False)) or "none"
        return f"Model(unit '{self.unit.name}'; effects {per})"

    def _repr_html_(self):
        c = self.channels[["channel", "effects", "val_rms"]].rename(columns={"val_rms": "validation rms (deg/h)"})
        c["effects"] = c["effects"].replace("", "—")
        return f"<b>model of the unit {self.unit.name}</b>" + c.to_html(index=False, float_format="{:.4f}".format)
