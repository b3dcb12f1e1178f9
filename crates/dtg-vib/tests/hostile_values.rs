//! Number-shaped hostile values (±1e308, 1e-308, NaN, ±inf, −0, and values
//! just inside the readers' ±1e150) in every numeric flag, record cell,
//! model number and scenario number of `dtg-vib`, run as a user would.
//!
//! Every run must end within seconds with exit 0 and finite, readable
//! output, or with a one-line `error:` and a non-zero exit (1, or 2 for a
//! flag clap refuses); never a panic or an abort; and every input file is
//! byte-identical afterwards. The regression tests at the end pin the
//! issue's cases to the messages that now replace them.

use cli_support::testing::{Binary, HOSTILE, s, scratch_dir};
use nav_sensors::record::Record;
use std::path::Path;
use std::path::PathBuf;
use std::sync::OnceLock;

/// `dtg-vib ARGS --quiet` under the harness's contract (exit 0, or one
/// `error:` line; within the time limit).
const BIN: Binary = Binary::new(env!("CARGO_BIN_EXE_dtg-vib")).appending(&["--quiet"]);

fn dir() -> &'static Path {
    scratch_dir("dtg-vib-hostile")
}

/// The demo scenario shortened to 12 s (600 samples), its record,
/// calibration and a small model: generated once from the scenario's seed.
struct Files {
    scenario: PathBuf,
    record: PathBuf,
    calib: PathBuf,
    model: PathBuf,
}

fn files() -> &'static Files {
    static F: OnceLock<Files> = OnceLock::new();
    F.get_or_init(|| {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenarios/demo.toml"
        ))
        .unwrap();
        assert!(text.contains("duration_s = 100.0"));
        let scenario = dir().join("short.toml");
        std::fs::write(
            &scenario,
            text.replacen("duration_s = 100.0", "duration_s = 12.0", 1),
        )
        .unwrap();
        let sim = dir().join("sim");
        assert_eq!(
            BIN.check(&["simulate", "--scenario", s(&scenario), "--out", s(&sim)])
                .code,
            0
        );
        let (record, calib) = (sim.join("record.csv"), sim.join("calibration.json"));
        let model = dir().join("model.json");
        let r = BIN.check(&[
            "fit",
            "--data",
            s(&record),
            "--calib",
            s(&calib),
            "--max-centers",
            "4",
            "--candidates",
            "40",
            "--out",
            s(&model),
        ]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        Files {
            scenario,
            record,
            calib,
            model,
        }
    })
}

fn snapshot(paths: &[&Path]) -> Vec<Vec<u8>> {
    paths.iter().map(|p| std::fs::read(p).unwrap()).collect()
}

/// A fit that succeeded wrote a model that loads, with finite scores.
fn model_is_usable(path: &Path) {
    let m = dtg_vib::unit_sensor::UnitModel::load(path).unwrap();
    for c in m.inner().channels() {
        assert!(c.scores().val_rms.is_finite(), "{}", path.display());
    }
}

/// Every numeric flag of `fit`, with every hostile value.
#[test]
fn fit_flags() {
    let f = files();
    let before = snapshot(&[&f.record, &f.calib]);
    let out = dir().join("flags.json");
    for flag in [
        "--window",
        "--train-fraction",
        "--max-centers",
        "--candidates",
        "--cutoff",
        "--filter-order",
        "--input-cutoff",
        "--ridge",
        "--seed",
        "--earth-rate",
        "--table-rate",
    ] {
        for v in HOSTILE {
            let value = if flag == "--table-rate" {
                format!("{v},0,0")
            } else {
                v.to_string()
            };
            let _ = std::fs::remove_file(&out);
            let mut args = vec!["fit", "--data", s(&f.record), "--calib", s(&f.calib)];
            if flag != "--max-centers" {
                args.extend(["--max-centers", "4"]);
            }
            if flag != "--candidates" {
                args.extend(["--candidates", "40"]);
            }
            args.extend([flag, &value, "--out", s(&out)]);
            let r = BIN.check(&args);
            if r.code == 0 {
                model_is_usable(&out);
            } else if r.code == 2 {
                assert!(
                    r.stderr.contains(flag) || r.stderr.contains(v),
                    "{flag} {v}: {}",
                    r.stderr
                );
            }
        }
    }
    assert!(
        before == snapshot(&[&f.record, &f.calib]),
        "an input changed"
    );
}

/// Every column of the record, with every hostile value, in `fit`,
/// `compensate` and `residues`.
#[test]
fn record_cells() {
    let f = files();
    let text = std::fs::read_to_string(&f.record).unwrap();
    let header: Vec<String> = text
        .lines()
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let model_before = snapshot(&[&f.model]);
    for (col, name) in header.iter().enumerate() {
        for v in HOSTILE {
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            let mut cells: Vec<&str> = lines[300].split(',').collect();
            cells[col] = v;
            lines[300] = cells.join(",");
            let data = dir().join(format!("cell-{name}.csv"));
            std::fs::write(&data, lines.join("\n") + "\n").unwrap();
            let out = dir().join("cell-out.csv");
            let model = dir().join("cell-model.json");
            for args in [
                vec![
                    "fit",
                    "--data",
                    s(&data),
                    "--max-centers",
                    "4",
                    "--candidates",
                    "40",
                    "--out",
                    s(&model),
                ],
                vec![
                    "compensate",
                    "--model",
                    s(&f.model),
                    "--data",
                    s(&data),
                    "--out",
                    s(&out),
                ],
                vec![
                    "residues",
                    "--model",
                    s(&f.model),
                    "--data",
                    s(&data),
                    "--out",
                    s(&out),
                ],
            ] {
                let _ = std::fs::remove_file(&out);
                let r = BIN.check(&args);
                if r.code == 0 && args[0] != "fit" {
                    // What was written reads back, so it is finite and bounded.
                    if args[0] == "compensate" {
                        Record::read_csv(&out).unwrap();
                    } else {
                        tabular::Table::read(&out).unwrap();
                    }
                } else if r.code != 0 && ["1e308", "-1e308", "NaN", "inf", "-inf"].contains(v) {
                    // Refused where it enters: the file, line and column.
                    assert!(
                        r.stderr.contains(&format!("{}:301:{}", s(&data), col + 1)),
                        "{args:?}: {}",
                        r.stderr
                    );
                }
            }
        }
    }
    assert!(model_before == snapshot(&[&f.model]), "the model changed");
}

/// Numbers of a model file replaced by hostile ones, in every command that
/// reads a model.
#[test]
fn model_numbers() {
    let f = files();
    let text = std::fs::read_to_string(&f.model).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let pointers = [
        "/model/channels/0/rbf/weights/data/0/0",
        "/model/channels/1/rbf/bias/0",
        "/model/channels/2/rbf/centres/data/0/0",
        "/model/channels/3/rbf/widths/uniform",
        "/model/preprocess/filter/cutoff_hz",
        "/model/dt_s",
        "/model/calibration/gyros/X/gg_ii_deg_h_g2",
        "/model/calibration/accels/az/k3_ug_per_g3",
    ];
    for p in pointers {
        assert!(v.pointer(p).is_some(), "{p} not in the model");
    }
    let data_before = snapshot(&[&f.record]);
    // JSON has no NaN or inf: those are refused as JSON; the rest as values.
    for value in ["1e308", "-1e308", "1e-308", "-0", "1e155", "1e149", "NaN"] {
        for p in pointers {
            // The value goes in as typed, not as serde_json would print it.
            let mut m = v.clone();
            *m.pointer_mut(p).unwrap() = serde_json::json!("HOSTILE");
            let edited = m.to_string().replacen("\"HOSTILE\"", value, 1);
            let path = dir().join("edited-model.json");
            std::fs::write(&path, &edited).unwrap();
            let out = dir().join("edited-out.csv");
            let report = dir().join("edited-report");
            for args in [
                vec![
                    "compensate",
                    "--model",
                    s(&path),
                    "--data",
                    s(&f.record),
                    "--out",
                    s(&out),
                ],
                vec![
                    "residues",
                    "--model",
                    s(&path),
                    "--data",
                    s(&f.record),
                    "--out",
                    s(&out),
                ],
                vec![
                    "diagnose",
                    "--model",
                    s(&path),
                    "--data",
                    s(&f.record),
                    "--json",
                ],
                vec![
                    "report",
                    "--model",
                    s(&path),
                    "--data",
                    s(&f.record),
                    "--out",
                    s(&report),
                ],
            ] {
                let _ = std::fs::remove_file(&out);
                let r = BIN.check(&args);
                if r.code == 0 && args[0] == "compensate" {
                    Record::read_csv(&out).unwrap();
                }
            }
        }
    }
    assert!(data_before == snapshot(&[&f.record]), "the record changed");
}

/// Numbers of the shipped scenarios replaced by hostile ones: `simulate`
/// refuses naming the file, or writes a record that reads back.
#[test]
fn scenario_numbers() {
    let f = files();
    let text = std::fs::read_to_string(&f.scenario).unwrap();
    let fields = [
        "latitude_deg = 8.5",
        "gain_db = 0.0",
        "initial_c = 22.0",
        "bias_deg_h = 2.1",
        "spin_hz = 200.0",
        "output_rate_hz = 50.0",
        "duration_s = 12.0",
        "time_constant_s = 60.0",
        "density_ug_per_rt_hz = 10.0",
        "relative = 0.01",
    ];
    for (k, field) in fields.iter().enumerate() {
        assert!(text.contains(field), "{field}");
        let key = field.split(" = ").next().unwrap();
        for v in HOSTILE.iter().chain(&["1e155"]) {
            // TOML spells them nan and inf.
            let v = v.to_lowercase();
            let bad = dir().join(format!("scenario-{k}.toml"));
            std::fs::write(&bad, text.replacen(field, &format!("{key} = {v}"), 1)).unwrap();
            let out = dir().join(format!("scenario-{k}"));
            let _ = std::fs::remove_dir_all(&out);
            let r = BIN.check(&["simulate", "--scenario", s(&bad), "--out", s(&out)]);
            if r.code == 0 {
                Record::read_csv(out.join("record.csv")).unwrap();
            } else {
                assert!(
                    r.stderr.contains(s(&bad)) || r.stderr.contains(s(&out)),
                    "{field} → {v}: {}",
                    r.stderr
                );
                assert!(
                    !out.join("record.csv").exists(),
                    "{field} → {v}: a record was written"
                );
            }
        }
    }
}

// ---- Regressions: each case of the issue, as it reads now. ----

/// A value the calibration carries past ±1e150 (an accelerometer's k3·a³ on
/// az = 1e149) is named with the column and record time, not "sample 1999
/// is not finite".
#[test]
fn calibration_overflow_is_named_with_its_time() {
    let f = files();
    let text = std::fs::read_to_string(&f.record).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let az = lines[0].split(',').position(|h| h == "az").unwrap();
    for l in lines.iter_mut().skip(1) {
        let mut cells: Vec<String> = l.split(',').map(str::to_string).collect();
        cells[az] = "1e149".into();
        *l = cells.join(",");
    }
    let data = dir().join("az-1e149.csv");
    std::fs::write(&data, lines.join("\n") + "\n").unwrap();
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&data),
        "--calib",
        s(&f.calib),
        "--out",
        "/dev/null",
    ]);
    assert!(
        err.contains("after calibration") && err.contains("t = 0.02 s") && !err.contains("sample"),
        "{err}"
    );
}

/// A temperature cell near 1e155 in `diagnose` is refused at its position
/// (it used to make the OLS scores NaN and selection never end).
#[test]
fn diagnose_refuses_a_huge_temperature_cell() {
    let f = files();
    let text = std::fs::read_to_string(&f.record).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let temp = lines[0].split(',').position(|h| h == "temp").unwrap();
    let mut cells: Vec<String> = lines[100].split(',').map(str::to_string).collect();
    cells[temp] = "1e155".into();
    lines[100] = cells.join(",");
    let data = dir().join("temp-1e155.csv");
    std::fs::write(&data, lines.join("\n") + "\n").unwrap();
    let err = BIN.refused(&["diagnose", "--model", s(&f.model), "--data", s(&data)]);
    assert!(
        err.contains(&format!("temp-1e155.csv:101:{}", temp + 1)),
        "{err}"
    );
}

/// Model weights edited to 1e155 are refused on load naming the field, in
/// `diagnose` and `compensate` (diagnose used to hang or print rms inf).
#[test]
fn edited_weights_are_refused_naming_the_field() {
    let f = files();
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&f.model).unwrap()).unwrap();
    *v.pointer_mut("/model/channels/0/rbf/weights/data/0/0")
        .unwrap() = serde_json::json!(1e155);
    let path = dir().join("weights-1e155.json");
    std::fs::write(&path, v.to_string()).unwrap();
    for args in [
        vec!["diagnose", "--model", s(&path), "--data", s(&f.record)],
        vec![
            "compensate",
            "--model",
            s(&path),
            "--data",
            s(&f.record),
            "--out",
            "/dev/null",
        ],
    ] {
        let err = BIN.refused(&args);
        assert!(
            err.contains("weights[0][0] = 1e155") && err.contains("±1e150"),
            "{args:?}: {err}"
        );
    }
}

/// A scenario whose temperature overflows the simulation writes nothing
/// (it used to write records of inf with exit 0).
#[test]
fn a_scenario_that_overflows_writes_nothing() {
    let f = files();
    let text = std::fs::read_to_string(&f.scenario).unwrap();
    let bad = dir().join("hot.toml");
    std::fs::write(
        &bad,
        text.replacen("initial_c = 22.0", "initial_c = 1e308", 1),
    )
    .unwrap();
    let out = dir().join("hot");
    let err = BIN.refused(&["simulate", "--scenario", s(&bad), "--out", s(&out)]);
    assert!(
        err.contains("nothing was written") && err.contains("column 'X'"),
        "{err}"
    );
    assert!(!out.exists());
}

/// Windows that never vary are said as such, not as the library's "use a
/// fixed width" (dtg-vib has no width flag).
#[test]
fn constant_windows_are_named_without_a_width_hint() {
    let f = files();
    let text = std::fs::read_to_string(&f.record).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let az = lines[0].split(',').position(|h| h == "az").unwrap();
    for l in lines.iter_mut().skip(1) {
        let mut cells: Vec<String> = l.split(',').map(str::to_string).collect();
        cells[az] = "1".into();
        *l = cells.join(",");
    }
    let data = dir().join("az-constant.csv");
    std::fs::write(&data, lines.join("\n") + "\n").unwrap();
    // az named: with `auto` (the default) this record, whose ax and ay
    // vary at 0.015 g and below, falls back to the axis that varies most.
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&data),
        "--window-signals",
        "az",
        "--out",
        "/dev/null",
    ]);
    assert!(
        err.contains("(az) do not vary") && !err.contains("fixed width"),
        "{err}"
    );
}

/// Inner folds emptied by the leakage gap name the settings behind it, not
/// "fold 1 of 226 samples has 0 training rows".
#[test]
fn inner_folds_too_short_name_the_settings() {
    let f = files();
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&f.record),
        "--window",
        "150",
        "--out",
        "/dev/null",
    ]);
    assert!(
        err.contains("cross-validation folds")
            && err.contains("--window")
            && !err.contains("fold 1 of"),
        "{err}"
    );
}

/// `--max-centers` beyond `--candidates` is refused at once (100,000,000
/// used to run past any time limit); `--candidates 0` never reaches a hint
/// proposing "≤ 0".
#[test]
fn centre_counts_are_refused_with_values_that_work() {
    let f = files();
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&f.record),
        "--max-centers",
        "100000000",
        "--out",
        "/dev/null",
    ]);
    assert!(err.contains("use --max-centers 1 to 400"), "{err}");
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&f.record),
        "--candidates",
        "0",
        "--out",
        "/dev/null",
    ]);
    assert!(
        err.contains("--candidates") && err.contains("≥ 1") && !err.contains("≤ 0"),
        "{err}"
    );
}
