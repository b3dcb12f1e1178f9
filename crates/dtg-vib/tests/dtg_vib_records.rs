//! Several records in one fit, and a model checked on a record it was not
//! fitted on (data simulated here from fixed seeds), on the paper's unit
//! through the one plug-in ([`UnitSensor`]).

mod paper_fit;

use dtg_vib::unit_sensor::check::DEFAULT_OUTSIDE_THRESHOLD;
use dtg_vib::unit_sensor::{UnitModel, UnitSensor};
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, UnitSimulation};
use paper_fit::{checked, fit, fit_records, named, options, signals, simulate};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use sysid::fit::record_scores;
use sysid::{Prepared, Preprocess, Sensor};

/// The paper's Z-axis random test (100 s) from `seed`.
fn z_test(seed: u64) -> UnitSimulation {
    let s = Scenario {
        seed,
        ..Scenario::paper_z_random()
    };
    simulate(&s)
}

/// A test whose vibration runs along all three axes.
fn triaxial(seed: u64) -> UnitSimulation {
    let s = Scenario {
        duration_s: 60.0,
        seed,
        ..Scenario::triaxial_clean()
    };
    simulate(&s)
}

/// The records prepared together (or one alone) with the loop's defaults.
fn prepare(records: &[(String, &Record)]) -> Result<Prepared<UnitSensor>, sysid::SysidError> {
    let owned = signals(records);
    Prepared::new_many(
        &paper_fit::sensor(None),
        &named(&owned),
        &Preprocess::default(),
    )
}

#[test]
fn records_are_prepared_alone_and_laid_end_to_end() {
    let (a, b) = (z_test(11).record, z_test(12).record);
    let pa = prepare(&[("a".to_string(), &a)]).unwrap();
    let pb = prepare(&[("b".to_string(), &b)]).unwrap();
    let named = [("a".to_string(), &a), ("b".to_string(), &b)];
    let ab = prepare(&named).unwrap();
    assert_eq!(ab.rows(), pa.rows() + pb.rows());
    let rows = ab.record_rows();
    assert_eq!(rows[1], ("b", pa.rows()..pa.rows() + pb.rows()));
    // B's rows are B prepared alone: its filter never saw A's samples.
    let n = pa.rows();
    for ch in Channel::ALL {
        let k = ch.index();
        assert_eq!(&ab.target(k)[n..], pb.target(k), "{ch}");
        assert_eq!(&ab.target(k)[..n], pa.target(k), "{ch}");
    }
    assert_eq!(ab.windows(0).row(n), pb.windows(0).row(0));
    let az = ab.signal_full("az").unwrap();
    let first = ab.first_sample();
    assert_eq!(&az[first + n..], &pb.signal_full("az").unwrap()[first..]);
    let y1 = Channel::Y1.index();
    let effects = [paper_fit::sensor(None).parse_effect(y1, "gg_IS").unwrap()];
    let col = ab.effect_columns_full(y1, &effects).unwrap();
    let alone = pb.effect_columns_full(y1, &effects).unwrap();
    assert_eq!(&col[0][first + n..], &alone[0][first..]);
}

#[test]
fn records_that_differ_are_refused_with_both_names() {
    let a = z_test(11).record;
    let mut cols = vec![];
    let b = Record::new(
        a.t().to_vec(),
        std::array::from_fn(|k| a.gyro_at(k).to_vec()),
        std::array::from_fn(|k| a.accel_at(k).to_vec()),
        {
            cols.push(("pressure_hpa".to_string(), vec![1013.0; a.len()]));
            cols
        },
    )
    .unwrap();
    let named = [("a.csv".to_string(), &a), ("b.csv".to_string(), &b)];
    let Err(err) = prepare(&named) else {
        panic!("records with other extra columns were prepared together");
    };
    let msg = err.to_string();
    assert!(
        msg.contains("a.csv") && msg.contains("b.csv") && msg.contains("extra columns"),
        "{msg}"
    );
}

#[test]
fn one_record_through_fit_records_is_fit() {
    let sim = z_test(11);
    let one = fit(&sim.record, Some(&sim.calibration), &options());
    let named = [("a".to_string(), &sim.record)];
    let (many, _) = fit_records(&named, Some(&sim.calibration), &options());
    // The window's signals chosen from the records name them in the
    // choice report: "a" here, nameless in a fit of one record. Everything
    // else is the same model.
    let choice = many.inner().choice().map(|c| c.window_signals.clone());
    let mut choice = choice.expect("the window's signals chosen from the record");
    assert_eq!(choice.len(), 1, "one choice: every gyro's");
    assert_eq!(choice[0].records, ["a"]);
    choice[0].records = vec![String::new()];
    let many = UnitModel::of(many.inner().clone().with_window_signals(choice));
    assert_eq!(one, many);
}

#[test]
fn each_record_validates_and_a_model_warns_outside_its_training_range() {
    let (a, b) = (z_test(21), z_test(22));
    let named = [("a".to_string(), &a.record), ("b".to_string(), &b.record)];
    let (model, prepared) = fit_records(&named, Some(&a.calibration), &options());
    let model = model.inner();
    assert_eq!(model.records(), ["a", "b"]);
    let per = record_scores(model, &prepared).unwrap();
    for (k, scores) in per.iter().enumerate() {
        let files: Vec<&str> = scores.iter().map(|s| s.file.as_str()).collect();
        assert_eq!(files, ["a", "b"]);
        // Same profile, same sensor: each record's rms near the pooled one.
        let pooled = model.channels()[k].scores().val_rms;
        for s in scores {
            assert!((s.val_rms / pooled - 1.0).abs() < 0.3, "{s:?} vs {pooled}");
        }
    }
    // Another run of the same test lies inside the training range of a
    // model of one run …
    let model = fit(&a.record, Some(&a.calibration), &options());
    let same = checked(&model, &z_test(23).record);
    let inside = same.outside_fraction.unwrap();
    assert!(inside < DEFAULT_OUTSIDE_THRESHOLD, "{inside}");
    assert!(same.warning.is_none(), "{:?}", same.warning);
    for c in &same.channels {
        // The run's turn-on bias differs (mean_after); the vibration-induced
        // part falls.
        let varying = (c.rms_after.powi(2) - c.mean_after.powi(2)).sqrt();
        assert!(varying < 0.8 * c.rms_before, "{c:?}");
    }
    // … a test that shakes along every axis does not, and is said to.
    let other = checked(&model, &triaxial(24).record);
    let outside = other.outside_fraction.unwrap();
    assert!(outside > 0.5, "{outside}");
    assert!(other.warning.as_deref().unwrap().contains("outside"));
}

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
}

fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = cli_support::testing::scratch_dir("dtg-vib-records").to_path_buf();
        for (name, seed) in [("a", 31), ("b", 32)] {
            z_test(seed).write_dir(d.join(name)).unwrap();
        }
        triaxial(24).write_dir(d.join("triaxial")).unwrap();
        d
    })
}

fn dtg(args: &[&str]) -> std::process::Output {
    bin().args(args).arg("--quiet").output().unwrap()
}

#[test]
fn the_command_line_fits_several_records_and_names_them_in_json() {
    let d = dir();
    let (a, b) = (d.join("a/record.csv"), d.join("b/record.csv"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let model = d.join("ab.json");
    let model = model.to_str().unwrap();
    let json = |args: &[&str]| -> serde_json::Value {
        let out = dtg(args);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let v = json(&[
        "fit",
        "--data",
        a,
        "--data",
        b,
        "--out",
        model,
        "--json",
        "--max-centers",
        "20",
    ]);
    let files = |v: &serde_json::Value| -> Vec<String> {
        v["channels"][0]["records"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                assert!(r["val_rms"].as_f64().unwrap() > 0.0);
                r["file"].as_str().unwrap().to_string()
            })
            .collect()
    };
    assert_eq!(files(&v), [a, b]);
    let v = json(&[
        "fit",
        "--data",
        a,
        "--data",
        b,
        "--split",
        "by-record",
        "--validate-on",
        b,
        "--out",
        model,
        "--json",
        "--max-centers",
        "20",
    ]);
    assert_eq!(files(&v), [b]);
    assert!(v["split"].as_str().unwrap().contains("by record"));
    let v = json(&[
        "fit",
        "--data",
        a,
        "--data",
        b,
        "--cv",
        "records",
        "--out",
        model,
        "--json",
        "--max-centers",
        "20",
    ]);
    assert_eq!(files(&v), [a, b]);
    assert_eq!(v["cv"], "records");
    // check: the contract keys.
    let v = json(&["check", "--model", model, "--data", a, "--json"]);
    for key in [
        "channel",
        "rms_before",
        "rms_after",
        "fit_percent",
        "rms_inside",
        "rms_outside",
    ] {
        assert!(v["channels"][0].get(key).is_some(), "{key}");
    }
    assert!(v["outside_fraction"].as_f64().is_some());
    assert!(v.get("warning").is_some());
}

/// `check`'s text says what `check --json` holds, compared alike: each
/// channel's spread after (its rms about the mean, as "rms before" is) next to
/// its mean, a negative fit said to be worse than the mean, what the reference
/// distance is, each residue "N× better" or "N× worse" (a worsening used to
/// print as a "reduction" of 0.16×), and the six residues pooled.
#[test]
fn check_text_compares_before_and_after_alike() {
    let d = dir();
    let (a, other) = (d.join("a/record.csv"), d.join("triaxial/record.csv"));
    let (a, other) = (a.to_str().unwrap(), other.to_str().unwrap());
    let model = d.join("a-text.json");
    let model = model.to_str().unwrap();
    let ok = |args: &[&str]| -> String {
        let out = dtg(args);
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    ok(&["fit", "--data", a, "--out", model, "--max-centers", "20"]);
    let args = ["check", "--model", model, "--data", other];
    let v: serde_json::Value =
        serde_json::from_str(&ok(&[&args[..], &["--json"]].concat())).unwrap();
    let text = ok(&args);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "channel  rms before  rms after  mean after  spread after   fit %   inside  outside  │ no fade: rms after  mean after  spread after  (deg/h)"
    );
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let mut worse_than_the_mean = vec![];
    for (c, line) in v["channels"].as_array().unwrap().iter().zip(&lines[1..7]) {
        let cells: Vec<&str> = line.split_whitespace().collect();
        let (rms, mean) = (f(&c["rms_after"]), f(&c["mean_after"]));
        let spread = (rms * rms - mean * mean).sqrt();
        assert_eq!(cells[0], c["channel"].as_str().unwrap());
        assert_eq!(cells[1], format!("{:.4}", f(&c["rms_before"])), "{line}");
        assert_eq!(cells[3], format!("{mean:.4}"), "{line}");
        assert_eq!(cells[4], format!("{spread:.4}"), "{line}");
        // After the bar, the model as fitted: its network part not faded.
        assert_eq!(cells[8], "│", "{line}");
        assert_eq!(
            cells[9],
            format!("{:.4}", f(&c["rms_after_unfaded"])),
            "{line}"
        );
        if f(&c["fit_percent"]) < 0.0 {
            worse_than_the_mean.push(cells[0]);
        }
    }
    assert!(
        lines[7].starts_with("rms before and spread after are about the mean"),
        "{text}"
    );
    let negative = lines.iter().find(|l| l.starts_with("fit % = ")).copied();
    match worse_than_the_mean.is_empty() {
        true => assert_eq!(negative, None, "{text}"),
        false => {
            let l = negative.unwrap_or_else(|| panic!("no line on negative fits: {text}"));
            let named = format!("below 0 on {}:", worse_than_the_mean.join(", "));
            assert!(
                l.contains(&named) && l.ends_with("worse than the mean"),
                "{l}"
            );
        }
    }
    assert!(
        text.contains("× the reference distance (99% of the model's own validation windows lie within it of a training point), outside beyond 1.5×"),
        "{text}"
    );
    // The residues, then the six pooled.
    let head = lines
        .iter()
        .position(|l| l.starts_with("residue "))
        .unwrap();
    assert_eq!(
        lines[head],
        "residue  rms before  rms after  (deg/h, every row)        change"
    );
    let change = |before: f64, after: f64| match before >= after {
        true => format!("{:.2}× better", before / after),
        false => format!("{:.2}× worse", after / before),
    };
    let residues = v["residues"].as_array().unwrap();
    let pooled =
        |key: &str| (residues.iter().map(|r| f(&r[key]).powi(2)).sum::<f64>() / 6.0).sqrt();
    let mut expected: Vec<(String, f64, f64)> = residues
        .iter()
        .map(|r| {
            let name = r["residue"].as_str().unwrap().to_string();
            (name, f(&r["rms_before"]), f(&r["rms_after"]))
        })
        .collect();
    expected.push(("pooled".into(), pooled("rms_before"), pooled("rms_after")));
    let rows = &lines[head + 1..head + 8];
    for ((name, before, after), line) in expected.iter().zip(rows) {
        let want = format!("{before:.4}  {after:>9.4}");
        assert!(
            line.trim_start().starts_with(&format!("{name}  ")),
            "{line}"
        );
        assert!(line.contains(&want), "{line} / {want}");
        assert!(line.ends_with(&change(*before, *after)), "{line}");
    }
    // This record makes some residue worse: the case the words are for.
    assert!(rows.iter().any(|l| l.ends_with("worse")), "{text}");
}

#[test]
fn bad_record_flags_say_what_to_do() {
    let d = dir();
    let (a, b) = (d.join("a/record.csv"), d.join("b/record.csv"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let refuses = |args: &[&str], want: &str| {
        let out = dtg(args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(!err.contains("panicked"), "{err}");
        assert!(err.contains(want), "{args:?}: {err}");
    };
    refuses(
        &[
            "fit",
            "--data",
            a,
            "--data",
            b,
            "--split",
            "by-record",
            "--out",
            "/dev/null",
        ],
        "--validate-on",
    );
    refuses(
        &[
            "fit",
            "--data",
            a,
            "--data",
            b,
            "--split",
            "by-record",
            "--validate-on",
            "c.csv",
            "--out",
            "/dev/null",
        ],
        "not one of the --data records",
    );
    refuses(
        &["fit", "--data", a, "--validate-on", a, "--out", "/dev/null"],
        "only with --split by-record",
    );
    refuses(
        &["fit", "--data", a, "--cv", "records", "--out", "/dev/null"],
        "two or more",
    );
    refuses(
        &["check", "--model", "missing.json", "--data", a],
        "missing.json",
    );
    refuses(
        &[
            "check",
            "--model",
            "m.json",
            "--data",
            a,
            "--outside-threshold",
            "2",
        ],
        "between 0 and 1",
    );
}
