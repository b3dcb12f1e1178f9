//! Mutation fuzzing of every reader: record CSV, rbf CSV, both model JSON
//! formats (rbf and dtg-vib), calibration JSON and scenario TOML.
//!
//! Each property starts from a valid file — the shipped scenarios, or a
//! record, calibration and models generated from a fixed seed — replaces one
//! cell or number with a hostile one (±1e308, 1e-308, NaN, inf, −0, 1e155,
//! text, any `f64`) or damages the structure, and requires: no panic; a
//! refusal names the file (and, for a CSV cell, its line and column); and
//! what is accepted stays finite through the next stage (pre-processing,
//! compensation, prediction, simulation) or is refused there, and anything
//! written can be read back.
//!
//! Case counts are small by default so CI stays within seconds;
//! `PROPTEST_CASES=N` sets every property's count (docs/rbf.md records a
//! long run).

use std::sync::OnceLock;

mod paper_fit;

use dtg_vib::unit_sensor::{
    Applied, UnitModel, UnitSensor, calibration_from_json, to_record, to_signals,
};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, simulate_unit};
use nav_sensors::unit::Unit;
use paper_fit::sensor;
use proptest::prelude::*;
use proptest::test_runner::Config;
use rbf::RbfModel;
use rbf::faer::Mat;
use sysid::{Prepared, Preprocess};

/// `PROPTEST_CASES` if set, else `default`.
fn config(default: u32) -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

/// Number-shaped (and not quite number-shaped) replacements.
const HOSTILE: &[&str] = &[
    "1e308",
    "-1e308",
    "1e-308",
    "-1e-308",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "-0",
    "0",
    "1e155",
    "-1e200",
    "1e150",
    "-1e150",
    "1.0000001e150",
    "",
    "abc",
    "1e",
    "--1",
    "0x10",
    "+5",
    "1_0",
    "9999999999999999999999",
    "4.9e-324",
];

/// A hostile replacement: one of [`HOSTILE`] or any `f64` (NaN, ±inf,
/// subnormals and the extremes included) as Rust prints it.
fn hostile() -> impl Strategy<Value = String> {
    prop_oneof![
        3 => proptest::sample::select(HOSTILE).prop_map(str::to_string),
        1 => any::<f64>().prop_map(|v| format!("{v}")),
        1 => any::<f64>().prop_map(|v| format!("{v:e}")),
    ]
}

/// The demo scenario shortened to 12 s (600 samples): enough rows for the
/// 50-sample windows, the filter and a split, small enough to fit in 0.1 s.
fn scenario() -> Scenario {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/demo.toml"
    ))
    .unwrap();
    let mut s = Scenario::from_toml(&text, "demo.toml").unwrap();
    s.duration_s = 12.0;
    s
}

struct Base {
    record: Record,
    record_csv: String,
    calibration: UnitCalibration,
    /// The calibration in the unit format, and the paper's (the fixture
    /// 5b6a72d wrote): both read through the one reader.
    calibration_json: [String; 2],
    model: UnitModel,
    /// The model file written now, and the paper's without a unit key (the
    /// fixture 5b6a72d wrote): both read through the one reader.
    model_json: [String; 2],
    rbf_csv: String,
    rbf_model: RbfModel,
    rbf_json: String,
}

fn base() -> &'static Base {
    static BASE: OnceLock<Base> = OnceLock::new();
    BASE.get_or_init(|| {
        let sim = paper_fit::simulate(&scenario());
        let mut buf = Vec::new();
        sim.record.write_to(&mut buf, "record.csv").unwrap();
        let record_csv = String::from_utf8(buf).unwrap();
        let mut options = paper_fit::options();
        options.recipe.settings.max_centres = 4;
        options.recipe.settings.candidates = 40;
        let model = paper_fit::fit(&sim.record, Some(&sim.calibration), &options);
        let path = std::env::temp_dir().join(format!("fuzz-readers-{}.json", std::process::id()));
        model.save(&path).unwrap();
        let model_json = [
            std::fs::read_to_string(&path).unwrap(),
            legacy("paper/model.json"),
        ];
        std::fs::remove_file(&path).unwrap();
        // The rbf CSV: a smooth surface of two inputs, seeded by construction.
        let mut rbf_csv = String::from("a,b,y\n");
        for i in 0..60 {
            let a = (i % 7) as f64 / 7.0;
            let b = (i % 11) as f64 / 11.0;
            rbf_csv.push_str(&format!("{a},{b},{}\n", (3.0 * a).sin() + b * b));
        }
        let x = Mat::from_fn(60, 2, |i, j| {
            [(i % 7) as f64 / 7.0, (i % 11) as f64 / 11.0][j]
        });
        let y = Mat::from_fn(60, 1, |i, _| {
            (3.0 * x[(i, 0)]).sin() + x[(i, 1)] * x[(i, 1)]
        });
        let params = rbf::ParamGuard::check(
            rbf::RbfParams::new()
                .kernel(rbf::Kernel::Cubic)
                .centres(rbf::CentreSelection::random(6))
                .seed(3),
        )
        .unwrap();
        let rbf_model = params.fit(x.as_ref(), y.as_ref()).unwrap();
        let mut buf = Vec::new();
        rbf_model.to_writer(&mut buf).unwrap();
        Base {
            record: sim.record.clone(),
            record_csv,
            calibration_json: [sim.calibration.to_json(), legacy("paper/calibration.json")],
            calibration: sim.calibration,
            model,
            model_json,
            rbf_csv,
            rbf_model,
            rbf_json: String::from_utf8(buf).unwrap(),
        }
    })
}

/// A fixture file of 5b6a72d's (tests/fixtures/legacy).
fn legacy(path: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/legacy");
    std::fs::read_to_string(dir.join(path)).unwrap()
}

/// The paper unit's record prepared as a fit would (the window's signals
/// chosen from the record), or the refusal.
fn prepared(r: &Record, c: Option<&UnitCalibration>) -> Option<Prepared<UnitSensor>> {
    let signals = to_signals(r).ok()?;
    Prepared::new(&sensor(c), &signals, &Preprocess::default()).ok()
}

/// Replaces the cell at (`line`, `col`) (both taken modulo the shape; line 0
/// is the header) with `value`; returns the text and the 1-based line and
/// column replaced.
fn replace_cell(text: &str, line: usize, col: usize, value: &str) -> (String, usize, usize) {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let l = 1 + line % (lines.len() - 1);
    let mut cells: Vec<&str> = lines[l].split(',').collect();
    let c = col % cells.len();
    cells[c] = value;
    lines[l] = cells.join(",");
    (lines.join("\n") + "\n", l + 1, c + 1)
}

/// Damage that is not a cell value: a cut, a dropped separator, a stray byte.
fn damage(text: &str, kind: u8, at: usize) -> String {
    let at = at % text.len();
    let at = (0..=at)
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    match kind % 4 {
        0 => text[..at].to_string(),
        1 => text.replacen(",", "", 1 + at % 5),
        2 => format!("{}\u{0}{}", &text[..at], &text[at..]),
        _ => format!("{}\n{}", &text[..at], &text[at..]),
    }
}

/// Byte spans of the number tokens of a JSON or TOML text.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts =
            b[i].is_ascii_digit() || (b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit));
        // Not inside a word (keys such as "rect_2n" or "k2_ug" hold digits).
        let inside_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if starts && !inside_word {
            let mut j = i + 1;
            while j < b.len() && (b[j].is_ascii_digit() || b"+-.eE".contains(&b[j])) {
                j += 1;
            }
            if j >= b.len() || !(b[j].is_ascii_alphabetic() || b[j] == b'_') {
                spans.push((i, j));
            }
            i = j;
        } else {
            i += 1;
        }
    }
    spans
}

/// Replaces number token `k` (modulo their count) with `value`.
fn replace_number(text: &str, k: usize, value: &str) -> String {
    let spans = number_spans(text);
    let (a, b) = spans[k % spans.len()];
    format!("{}{value}{}", &text[..a], &text[b..])
}

/// Every value of a record is finite and within the readers' bound.
fn record_bounded(r: &Record) -> bool {
    let ok = |v: &[f64]| {
        v.iter()
            .all(|x| x.is_finite() && x.abs() <= tabular::MAX_MAGNITUDE)
    };
    ok(r.t())
        && Channel::ALL
            .iter()
            .all(|&c| ok(r.gyro_named(c.name()).unwrap()))
        && nav_sensors::geometry::Axis::ALL
            .iter()
            .all(|&a| ok(r.accel_named(a.column()).unwrap()))
        && r.extra_names().iter().all(|n| ok(r.extra(n).unwrap()))
}

/// A record written to memory reads back, or the writer refused it.
fn writes_readably(r: &Record) -> Result<(), TestCaseError> {
    let mut buf = Vec::new();
    if r.write_to(&mut buf, "out.csv").is_ok() {
        let back = Record::from_reader(buf.as_slice(), "out.csv");
        prop_assert!(back.is_ok(), "written but unreadable: {:?}", back.err());
    }
    Ok(())
}

/// Accepted records stay finite through pre-processing (with the ground
/// calibration) or are refused there with a message.
fn preprocess_finite(r: &Record, c: Option<&UnitCalibration>) -> Result<(), TestCaseError> {
    if let Some(p) = prepared(r, c) {
        for ch in Channel::ALL {
            prop_assert!(
                p.target_full(ch.index()).iter().all(|v| v.is_finite()),
                "{ch}: NaN target"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    /// Record CSV: a hostile cell is refused at its file:line:column, or
    /// read as a bounded number that pre-processes to finite targets.
    #[test]
    fn record_csv_cells(line in any::<usize>(), col in any::<usize>(), value in hostile()) {
        let b = base();
        let (text, l, c) = replace_cell(&b.record_csv, line, col, &value);
        match Record::from_reader(text.as_bytes(), "rec.csv") {
            Ok(r) => {
                prop_assert!(record_bounded(&r));
                preprocess_finite(&r, Some(&b.calibration))?;
                writes_readably(&r)?;
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.starts_with("rec.csv"), "{msg}");
                // A bad number is named where it is; a time column made
                // non-increasing or uneven is a record-level refusal.
                if !(msg.contains(" t ") || msg.contains("time") || msg.contains("interval")) {
                    prop_assert!(msg.contains(&format!("rec.csv:{l}:{c}")), "{value} at {l}:{c}: {msg}");
                }
            }
        }
    }

    /// Record CSV with structural damage: refused naming the file, or read
    /// bounded.
    #[test]
    fn record_csv_structure(kind in any::<u8>(), at in any::<usize>()) {
        let b = base();
        let text = damage(&b.record_csv, kind, at);
        match Record::from_reader(text.as_bytes(), "rec.csv") {
            Ok(r) => {
                prop_assert!(record_bounded(&r));
                preprocess_finite(&r, None)?;
            }
            Err(e) => prop_assert!(e.to_string().starts_with("rec.csv"), "{e}"),
        }
    }

    /// rbf CSV: every numeric column reads bounded, or the cell is named.
    #[test]
    fn rbf_csv_cells(line in any::<usize>(), col in any::<usize>(), value in hostile(),
                     kind in any::<u8>(), at in any::<usize>(), structural in any::<bool>()) {
        let b = base();
        let (text, l, c) = if structural {
            (damage(&b.rbf_csv, kind, at), 0, 0)
        } else {
            replace_cell(&b.rbf_csv, line, col, &value)
        };
        match tabular::Table::from_reader(text.as_bytes(), "d.csv") {
            Ok(t) => {
                for name in ["a", "b", "y"] {
                    match t.numeric(name) {
                        Ok(v) => prop_assert!(v.iter().all(|x| x.is_finite() && x.abs() <= tabular::MAX_MAGNITUDE)),
                        Err(e) => {
                            let msg = e.to_string();
                            prop_assert!(msg.starts_with("d.csv"), "{msg}");
                            if !structural && msg.contains(&format!("column '{name}'")) {
                                prop_assert!(msg.contains(&format!("d.csv:{l}:{c}")), "{msg}");
                            }
                        }
                    }
                }
            }
            Err(e) => prop_assert!(e.to_string().starts_with("d.csv"), "{e}"),
        }
    }

    /// Calibration JSON: a hostile coefficient is refused naming the file,
    /// or pre-processing stays finite (or refuses with the record time).
    #[test]
    fn calibration_json(format in 0usize..2, k in any::<usize>(), value in hostile()) {
        let b = base();
        let text = replace_number(&b.calibration_json[format], k, &value);
        match calibration_from_json(&text, "cal.json") {
            Ok(c) => {
                preprocess_finite(&b.record, Some(&c))?;
                if let Some(p) = prepared(&b.record, Some(&c)) {
                    match to_record(&Unit::paper(), p.calibrated()) {
                        Ok(r) => writes_readably(&r)?,
                        Err(e) => prop_assert!(false, "calibrated record: {e}"),
                    }
                }
            }
            Err(e) => prop_assert!(e.to_string().contains("cal.json"), "{e}"),
        }
    }

    /// dtg-vib model JSON: a hostile number is refused naming the file, or
    /// the model compensates the record to finite values (or refuses), and
    /// what compensate would write reads back.
    #[test]
    fn dtg_vib_model_json(format in 0usize..2, k in any::<usize>(), value in hostile()) {
        let b = base();
        let text = replace_number(&b.model_json[format], k, &value);
        let records = [("r".to_string(), &b.record)];
        match UnitModel::from_json(&text, std::path::Path::new("m.json")) {
            Ok(m) => {
                if let Some(comp) = Applied::unsplit(&m, &records).ok().and_then(|a| a.compensated().ok()) {
                    for comp in &comp {
                        prop_assert!((0..comp.gyro_names().len()).all(|k| comp.gyro_at(k).iter().all(|v| !v.is_nan())));
                        writes_readably(comp)?;
                    }
                }
            }
            Err(e) => prop_assert!(e.to_string().starts_with("m.json"), "{e}"),
        }
        // The unmutated models are the control: they must load and apply.
        prop_assert!(Applied::unsplit(&b.model, &records).is_ok());
        let unmutated = UnitModel::from_json(&b.model_json[format], std::path::Path::new("m.json"));
        prop_assert!(Applied::unsplit(&unmutated.unwrap(), &records).is_ok());
    }

    /// rbf model JSON: a hostile number is refused, or the model loads with
    /// every number bounded (it saves and loads back identically). Bounded
    /// numbers do not make bounded predictions (a cubic kernel on a centre at
    /// 1e148 overflows): those must be what the writer refuses.
    #[test]
    fn rbf_model_json(k in any::<usize>(), value in hostile()) {
        let b = base();
        let text = replace_number(&b.rbf_json, k, &value);
        if let Ok(m) = RbfModel::from_reader(text.as_bytes()) {
            let mut buf = Vec::new();
            prop_assert!(m.to_writer(&mut buf).is_ok(), "a loaded model must save");
            prop_assert_eq!(&RbfModel::from_reader(buf.as_slice()).unwrap(), &m);
            if m.dim() == 2 {
                let x = Mat::from_fn(5, 2, |i, j| (i + j) as f64 / 5.0);
                let y = m.predict(x.as_ref());
                let col: Vec<f64> = (0..y.nrows()).map(|i| y[(i, 0)]).collect();
                let bounded = col.iter().all(|v| v.is_finite() && v.abs() <= tabular::MAX_MAGNITUDE);
                prop_assert_eq!(
                    bounded,
                    tabular::first_unwritable("p.csv", &["prediction"], &[&col]).is_none()
                );
            }
        }
        prop_assert_eq!(&RbfModel::from_reader(b.rbf_json.as_bytes()).unwrap(), &b.rbf_model);
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// Scenario TOML (every shipped scenario): a hostile number is refused
    /// naming the file or the field, or the scenario, shortened to 2 s,
    /// simulates to a record that writes readably (or is refused unwritten).
    #[test]
    fn scenario_toml(file in 0usize..4, k in any::<usize>(), value in hostile()) {
        let name = ["demo", "paper_z_random", "triaxial_clean", "triaxial_hidden"][file];
        let text = std::fs::read_to_string(format!(
            "{}/../../scenarios/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let text = replace_number(&text, k, &value);
        let Ok(mut s) = Scenario::from_toml(&text, "s.toml") else {
            return Ok(());
        };
        if s.validate().is_err() {
            return Ok(());
        }
        // Bounded work: 2 s at the scenario's rates (validation caps them).
        s.duration_s = s.duration_s.min(2.0);
        if s.validate().is_err() || s.output_samples() * s.oversampling() > 200_000 {
            return Ok(());
        }
        if let Ok(sim) = simulate_unit(&Unit::paper(), &s) {
            writes_readably(&sim.record)?;
        }
    }
}

#[test]
fn number_spans_find_values_not_key_digits() {
    let spans = number_spans(r#"{"k2_ug": -1.5e3, "rect_2n": [2, 0.25]}"#);
    assert_eq!(spans.len(), 3);
}
