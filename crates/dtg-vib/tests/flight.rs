//! The loop on a moving redundant unit (issue 34 §1, §2 and its
//! acceptance): the real three-IMU quadrotor flights of
//! `data/realdata/multi-imu/` with `units/multi-imu.toml`, no rate
//! reference. The unit turns, so each channel is fitted in parity; the
//! dynamic effects (scale factor, misalignment, the rate's and the
//! accelerometers' FIR taps) are named with intervals; fitted on the first
//! half of `qdr_horizontal_path11.csv`, the pooled parity rms on its second
//! half is at most 0.85 × the linear baseline's (2.070 deg/s, the research
//! report's numpy recipe); the same on `qdr_vertical_path1.csv` fitted on
//! itself (0.85 × 1.713); and `check` of the path_11 model on the vertical
//! flight says how much it transfers (it does not: the timing and vibration
//! terms belong to one recording).

use std::path::Path;
use std::process::Output;

mod workspace_cli;
use workspace_cli::dtg_vib;

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn json(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", text(o));
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", text(o)))
}

const H: &str = "data/realdata/multi-imu/qdr_horizontal_path11.csv";
const V: &str = "data/realdata/multi-imu/qdr_vertical_path1.csv";
const UNIT: &str = "units/multi-imu.toml";
/// Half the flights' 8.33-ms output interval, ms: the bound on a relative
/// delay between IMUs synchronised within microseconds.
const HALF_SAMPLE_MS: f64 = 1000.0 / 120.0 / 2.0;
/// The recommended causal linear model per gyro (research report §4).
const EFFECTS: &str = "sf@0..4,ma_*@0..4,acc:*@0..5";

/// `COMMAND` on the flight unit with the linear model's flags.
fn linear<'a>(command: &'a str, data: &'a str, effects: &'a str, more: &[&'a str]) -> Vec<&'a str> {
    workspace_cli::linear(command, UNIT, data, effects, more)
}

/// Fits `data` with `effects` (the loop's blocked split: first half trains, second
/// validates) into `out`; returns the fit's JSON, after checking it said
/// in one line that it fits in parity and what that cannot observe.
fn fit(data: &str, effects: &str, out: &Path) -> serde_json::Value {
    let o = dtg_vib(&linear(
        "fit",
        data,
        effects,
        &["--json", "--out", out.to_str().unwrap()],
    ));
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    let note: Vec<&str> = e
        .lines()
        .filter(|l| l.contains("fitted in parity"))
        .collect();
    assert_eq!(note.len(), 1, "{e}");
    assert!(note[0].contains("is not, and is not fitted"), "{e}");
    // The declared units hold (deg/s, m/s²): the accelerometers read the
    // rotors' thrust, so the tilt check cannot tell and says nothing.
    assert!(!e.contains("warning"), "{e}");
    json(&o)
}

/// The pooled rms (deg/s) of a residue list, before and after: √(mean of
/// the residues' mean squares), the rms per parity residue (V has
/// orthonormal rows, so this is √(mean ‖P r‖² / (n − 3))).
fn pooled(list: &serde_json::Value, before: &str, after: &str) -> (f64, f64) {
    let rows = list.as_array().expect("a residue list");
    let p = |k: &str| {
        let ms = rows
            .iter()
            .map(|r| r[k].as_f64().unwrap().powi(2))
            .sum::<f64>();
        (ms / rows.len() as f64).sqrt() / 3600.0
    };
    assert_eq!(rows.len(), 6, "nine gyros on three axes: six residues");
    (p(before), p(after))
}

/// Pooled parity rms on the validation half of `data` under `model`.
fn validation_pooled(model: &Path, data: &str, csv: &Path) -> (f64, f64) {
    let r = json(&dtg_vib(&[
        "residues",
        "--model",
        model.to_str().unwrap(),
        "--data",
        data,
        "--out",
        csv.to_str().unwrap(),
        "--json",
    ]));
    pooled(&r["validation"], "rms_before", "rms_after")
}

#[test]
fn the_flights_are_fitted_in_parity_and_meet_the_acceptance() {
    let dir = tempfile::tempdir().unwrap();
    let mh = dir.path().join("path11.json");
    let fitted = fit(H, EFFECTS, &mh);
    // The effects are named with intervals: every channel's scale factor,
    // misalignments, rate taps and accelerometer taps, each with its unit
    // and a 95% interval about its value.
    let channels = fitted["channels"].as_array().unwrap();
    assert_eq!(channels.len(), 9);
    for c in channels {
        let e = &c["effect_coefficients"];
        assert_eq!(e.as_object().unwrap().len(), 5 + 10 + 54, "{c}");
        for (id, unit) in [("sf", "ppm"), ("sf@4", "ppm"), ("acc:a3z@5", "deg/h/g")] {
            let ci = e[id]["ci95"].as_array().unwrap();
            let v = e[id]["value"].as_f64().unwrap();
            assert!(ci[0].as_f64().unwrap() < v && v < ci[1].as_f64().unwrap());
            assert_eq!(e[id]["unit"], unit);
        }
    }
    assert_eq!(channels[0]["effect_coefficients"]["ma_y"]["unit"], "µrad");
    // Each tap family read as a filter: g1x's sf (delay and gain per band
    // to the 60 Hz Nyquist frequency) and its twelve families in all.
    let families = channels[0]["frequency_response"].as_array().unwrap();
    assert_eq!(families.len(), 1 + 2 + 9, "{families:?}");
    for f in families {
        let line: Vec<String> = f["bands"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| {
                let (g, hz) = (&b["gain"], &b["band_hz"]);
                format!(
                    "{:.0}–{:.0} Hz {:.4e} [{:.4e}, {:.4e}]",
                    hz[0].as_f64().unwrap(),
                    hz[1].as_f64().unwrap(),
                    g["value"].as_f64().unwrap(),
                    g["ci95"][0].as_f64().unwrap(),
                    g["ci95"][1].as_f64().unwrap()
                )
            })
            .collect();
        assert_eq!(line.len(), 4);
        println!(
            "path_11 g1x {} ({}): {}",
            f["family"],
            f["unit"],
            line.join(", ")
        );
    }
    // The delay the sf taps read as a filter: within half an output
    // interval, as the `delay` effect (see below).
    let delay = &families[0]["delay_ms"];
    println!("path_11 g1x sf delay, ms: {delay}");
    let ci = [0, 1].map(|k| delay["ci95"][k].as_f64().unwrap());
    assert!(-HALF_SAMPLE_MS < ci[0] && ci[1] < HALF_SAMPLE_MS, "{delay}");
    let (before, after) = validation_pooled(&mh, H, &dir.path().join("rh.csv"));
    // Before: the research recipe's 5.149 deg/s (its training mean removed).
    assert!((before - 5.149).abs() < 0.01, "before {before}");
    assert!(
        after <= 0.85 * 2.070,
        "path_11: pooled parity rms {after} deg/s > 1.760"
    );

    let mv = dir.path().join("path1.json");
    fit(V, EFFECTS, &mv);
    let (before_v, after_v) = validation_pooled(&mv, V, &dir.path().join("rv.csv"));
    assert!(before_v > 3.0 && before_v < 4.5, "before {before_v}");
    assert!(
        after_v <= 0.85 * 1.713,
        "path_1: pooled parity rms {after_v} deg/s > 1.456"
    );

    // The path_11 model on the vertical flight: check says how much it
    // transfers, on the pooled parity residue; it makes it worse.
    let o = dtg_vib(&[
        "check",
        "--model",
        mh.to_str().unwrap(),
        "--data",
        V,
        "--json",
    ]);
    let c = json(&o);
    let (b, a) = pooled(&c["residues"], "rms_before", "rms_after");
    assert!(a > b, "path_11's model on path_1: pooled {b} → {a} deg/s");
    let o = dtg_vib(&["check", "--model", mh.to_str().unwrap(), "--data", V]);
    let t = text(&o);
    assert!(t.contains("pooled") && t.contains("worse"), "{t}");
    assert!(t.contains("fitted in parity"), "{t}");
}

/// The other commands work on a model fitted in parity: compensate writes
/// the log, allan's before and after are both free of the motion (no
/// "turns" warning), diagnose ranks the dynamic effects, and export writes
/// the equations.
#[test]
fn the_commands_work_on_a_model_fitted_in_parity() {
    let dir = tempfile::tempdir().unwrap();
    let m = dir.path().join("path1.json");
    let fitted = fit(V, "sf,ma_*,delay", &m);
    let delay = &fitted["channels"][0]["effect_coefficients"]["delay"];
    assert_eq!(delay["unit"], "ms", "{fitted}");
    // g1x's delay against the other gyros, on the whole flight and on each
    // half fitted alone: the IMUs are synchronised and IMU 2 and 3
    // interpolated onto IMU 1's time stamps within microseconds
    // (data/realdata/multi-imu/README.md), so a relative delay is a
    // fraction of the 8.33-ms output interval: each 95% interval lies
    // within half of it. (The halves' estimates, 0.58 ± 0.10 and 0.21 ±
    // 0.10 ms, differ by 2.5 joint standard errors: the interval is not
    // asserted to cover the other half's value.)
    let halves = flight_halves(dir.path(), V).map(|half| {
        let out = half.with_extension("json");
        fit(half.to_str().unwrap(), "sf,ma_*,delay", &out)["channels"][0]["effect_coefficients"]
            ["delay"]
            .clone()
    });
    for d in std::iter::once(delay).chain(&halves) {
        let ci = [0, 1].map(|k| d["ci95"][k].as_f64().unwrap());
        println!(
            "path_1 g1x delay, ms: {} [{}, {}]",
            d["value"], ci[0], ci[1]
        );
        assert!(
            -HALF_SAMPLE_MS < ci[0] && ci[1] < HALF_SAMPLE_MS,
            "g1x's delay {d} is not within ±{HALF_SAMPLE_MS} ms"
        );
    }
    let model = m.to_str().unwrap();
    let out = dir.path().join("c.csv");
    let run = |args: &[&str]| {
        let o = dtg_vib(args);
        assert!(o.status.success(), "{args:?}: {}", text(&o));
        text(&o)
    };
    let t = run(&[
        "compensate",
        "--model",
        model,
        "--data",
        V,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(t.contains("the unit's own least-squares rate"), "{t}");
    // One header, then every sample from the first full window (49) on.
    assert_eq!(
        std::fs::read_to_string(&out).unwrap().lines().count(),
        1 + 3901 - 49
    );
    let t = run(&["allan", "--model", model, "--data", V]);
    assert!(!t.contains("the unit turns") && t.contains("after"), "{t}");
    let t = run(&["diagnose", "--model", model, "--data", V]);
    assert!(t.contains("validation rms"), "{t}");
    // What parity cannot observe, one line per rate family (issue 34 §2);
    // against a table rate the lines say each gyro's own (dtg_vib_cli.rs).
    for line in [
        "sf, sf@k (scale-factor error): in parity (no rate reference) only its differences between gyros are observable; a scale-factor error equal on every gyro is not",
        "ma_x, ma_y, ma_z, ma_*@k (misalignment / cross-axis sensitivity): in parity (no rate reference) only its differences between gyros are observable; a misalignment common to every gyro (the whole unit turned) is not",
        "delay, sf@1..4 (the gyro's frequency response to the rate): in parity (no rate reference) only its differences between gyros are observable; a delay or bandwidth every gyro shares is not",
    ] {
        assert!(t.contains(line), "{t}");
    }
    let ex = dir.path().join("ex");
    run(&[
        "export",
        "--model",
        model,
        "--lang",
        "text",
        "--out",
        ex.to_str().unwrap(),
    ]);
    let eq = std::fs::read_to_string(ex.join("equations.txt")).unwrap();
    assert!(eq.contains("delay: time delay"), "{eq}");
}

/// The two halves of the record `data` (its header on each), written
/// into `dir`.
fn flight_halves(dir: &Path, data: &str) -> [std::path::PathBuf; 2] {
    let text = std::fs::read_to_string(workspace_cli::root().join(data)).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let (header, rows) = lines.split_first().unwrap();
    let mid = rows.len() / 2;
    [("first", &rows[..mid]), ("second", &rows[mid..])].map(|(name, part)| {
        let path = dir.join(format!("{name}-half.csv"));
        let body: Vec<&str> = std::iter::once(*header)
            .chain(part.iter().copied())
            .collect();
        std::fs::write(&path, body.join("\n") + "\n").unwrap();
        path
    })
}

/// The first 10 s of the vertical flight (1200 rows), written into `dir`.
fn first_10_s(dir: &Path) -> std::path::PathBuf {
    let text_v = std::fs::read_to_string(workspace_cli::root().join(V)).unwrap();
    let cut = dir.join("cut.csv");
    let head: Vec<&str> = text_v.lines().take(1201).collect();
    std::fs::write(&cut, head.join("\n") + "\n").unwrap();
    cut
}

/// A fit of the multi-IMU unit on `data` of 5 centres, raw windows and no
/// smoother (seconds on 10 s of flight), written to `model`, with `more`
/// arguments.
fn small_fit(data: &Path, model: &Path, more: &[&str]) -> Output {
    let mut args = vec!["fit", "--unit", UNIT, "--data", data.to_str().unwrap()];
    args.extend(["--max-centres", "5", "--input", "raw", "--smoother", "none"]);
    args.extend(more);
    args.extend(["--out", model.to_str().unwrap()]);
    dtg_vib(&args)
}

/// A window may read any IMU's accelerometers (issue 34 §3: each gyro's
/// own IMU's are its operating signals), not only the first IMU's that
/// place the operating point; a gyro output is still refused, naming
/// what a window may read.
#[test]
fn a_window_reads_any_imus_accelerometers() {
    let dir = tempfile::tempdir().unwrap();
    let cut = first_10_s(dir.path());
    let model = dir.path().join("m.json");
    let args = |signals: &'static str| {
        let mut a = vec!["fit", "--unit", UNIT, "--data", cut.to_str().unwrap()];
        a.extend(["--window-signals", signals, "--max-centres", "5"]);
        a.extend(["--out", model.to_str().unwrap()]);
        a
    };
    let o = dtg_vib(&args("a2x,a2y,a2z"));
    assert!(o.status.success(), "{}", text(&o));
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&model).unwrap()).unwrap();
    // A named list is every channel's: no per-channel lists, no choice.
    assert_eq!(
        m["model"]["preprocess"]["window"]["signals"],
        serde_json::json!(["a2x", "a2y", "a2z"])
    );
    assert!(
        m["model"]["preprocess"]["window"]["channels"].is_null(),
        "{}",
        m["model"]["preprocess"]["window"]
    );
    assert!(m["model"]["choice"]["window_signals"].is_null());
    let o = dtg_vib(&args("g1x"));
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(
        t.contains("window signal 'g1x' cannot be windowed")
            && t.contains("(ax, ay, az, a2x, a2y, a2z, a3x, a3y, a3z)"),
        "{t}"
    );
}

/// By default (`--window-signals auto`) each gyro's network reads its own
/// IMU's accelerometers (issue 34 §3): the model file names each channel's
/// signals, all of its own IMU, and `fit --json` holds one choice per IMU
/// naming its gyros.
#[test]
fn each_gyros_window_reads_its_own_imus_accelerometers_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let cut = first_10_s(dir.path());
    let model = dir.path().join("m.json");
    let fitted = json(&small_fit(&cut, &model, &["--json"]));
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&model).unwrap()).unwrap();
    let window = &m["model"]["preprocess"]["window"];
    let own = |imu: usize| match imu {
        1 => ["ax", "ay", "az"].map(String::from),
        i => ["x", "y", "z"].map(|a| format!("a{i}{a}")),
    };
    let lists: Vec<Vec<String>> = serde_json::from_value(window["channels"].clone()).unwrap();
    assert_eq!(lists.len(), 9, "{window}");
    for (k, list) in lists.iter().enumerate() {
        assert!(!list.is_empty(), "{window}");
        assert!(
            list.iter().all(|s| own(k / 3 + 1).contains(s)),
            "gyro {k}: {list:?}"
        );
    }
    for (file, what) in [
        (&m["model"]["choice"], "model file"),
        (&fitted["choice"], "--json"),
    ] {
        let choices = file["window_signals"]
            .as_array()
            .unwrap_or_else(|| panic!("{what}: {file}"));
        assert_eq!(choices.len(), 3, "{what}");
        for (i, c) in choices.iter().enumerate() {
            let gyros: Vec<String> = ["x", "y", "z"]
                .iter()
                .map(|a| format!("g{}{a}", i + 1))
                .collect();
            assert_eq!(c["channels"], serde_json::json!(gyros), "{what}");
            assert_eq!(c["taken"], serde_json::json!(lists[3 * i]), "{what}");
            let measured: Vec<&str> = c["signals"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s["signal"].as_str().unwrap())
                .collect();
            assert_eq!(measured, own(i + 1), "{what}");
        }
    }
    // The model file reads back and its text export names each IMU's window.
    let o = dtg_vib(&[
        "export",
        "--lang",
        "text",
        "--model",
        model.to_str().unwrap(),
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("## Window of g2x, g2y, g2z\n"), "{t}");
}

/// An IMU whose accelerometers are constant (a still IMU, a dead triad)
/// does not fail a fit with `--window-signals auto` (the default): its
/// gyros' windows are chosen among every accelerometer, one note naming
/// the IMU, and the other IMUs' choices stand.
#[test]
fn an_imu_of_constant_accelerometers_falls_back_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let cut = first_10_s(dir.path());
    let csv = std::fs::read_to_string(&cut).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let dead: Vec<usize> = ["a2x", "a2y", "a2z"]
        .iter()
        .map(|a| header.iter().position(|h| h == a).unwrap())
        .collect();
    let mut still = header.join(",") + "\n";
    for line in lines {
        let mut row: Vec<&str> = line.split(',').collect();
        dead.iter().for_each(|&k| row[k] = "0.5");
        still += &(row.join(",") + "\n");
    }
    let data = dir.path().join("still-imu2.csv");
    std::fs::write(&data, still).unwrap();
    let model = dir.path().join("m.json");
    let o = small_fit(&data, &model, &[]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    let notes: Vec<&str> = t
        .lines()
        .filter(|l| l.starts_with("note:") && l.contains("constant in every record"))
        .collect();
    assert_eq!(notes.len(), 1, "{t}");
    assert!(
        notes[0].starts_with("note: IMU imu2's accelerometers (a2x, a2y, a2z) are constant in every record (a still IMU or a dead triad): the windows of g2x, g2y, g2z read "),
        "{t}"
    );
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&model).unwrap()).unwrap();
    let lists: Vec<Vec<String>> =
        serde_json::from_value(m["model"]["preprocess"]["window"]["channels"].clone()).unwrap();
    assert!(
        lists[3..6].iter().flatten().all(|s| !s.starts_with("a2")),
        "{lists:?}"
    );
    assert!(
        lists[0]
            .iter()
            .all(|s| ["ax", "ay", "az"].contains(&s.as_str())),
        "{lists:?}"
    );
    assert!(lists[6].iter().all(|s| s.starts_with("a3")), "{lists:?}");
}

/// `explain` and `report` work in parity too (issue 34 §1), on the first
/// 10 s of the vertical flight (1200 rows: seconds, not the whole flight):
/// explain says it fits in parity and runs its first round's diagnosis,
/// report writes its page with the pooled parity residue.
#[test]
fn explain_and_report_work_in_parity() {
    let dir = tempfile::tempdir().unwrap();
    let cut = first_10_s(dir.path());
    let (cut, model) = (cut.to_str().unwrap(), dir.path().join("m.json"));
    let o = dtg_vib(&linear(
        "explain",
        cut,
        "sf",
        &["--max-rounds", "1", "--out", model.to_str().unwrap()],
    ));
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("fitted in parity") && t.contains("round 1:"),
        "{t}"
    );
    let out = dir.path().join("report");
    let o = dtg_vib(&[
        "report",
        "--model",
        model.to_str().unwrap(),
        "--data",
        cut,
        "--out",
        out.to_str().unwrap(),
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains(" pooled "), "{t}");
    assert!(out.join("index.html").exists(), "{t}");
}
