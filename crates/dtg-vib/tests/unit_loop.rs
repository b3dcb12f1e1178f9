//! Issue 22's acceptance on units other than the paper's: the loop of the
//! demo (simulate, fit, diagnose, add, refit) on simulated records of the
//! built-in `tetra`, `triad` and `dual-triad` units with hidden effects
//! names exactly those effects on exactly their channels, each 95% interval
//! covers the truth, a clean twin gets nothing, and the refit's validation
//! rms is within 1.1× the clean twin's; the paper's unit renamed, reordered
//! and logged in deg/s and m/s² gives the paper's fit; and the command line
//! takes `--unit` and refuses what is not observable in one line.
//!
//! Each CI test runs one fixed seed. The rates over seeds (false alarms on
//! clean records, power, coverage) are the `#[ignore]`d test at the end
//! (measured: no false alarm in 60 clean records, the hidden effects exactly
//! in 60 of 60, coverage 77 of 80 intervals):
//! `cargo test --release -p dtg-vib --test unit_loop -- --ignored --nocapture`.

use cli_support::testing::{Binary, s, scratch_dir};
use dtg_vib::unit_sensor::{RateReference, UnitEffect, UnitSensor, to_signals};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, UnitHiddenEffect, simulate_unit};
use nav_sensors::unit::Unit;
use std::collections::BTreeMap;

mod loop_run;
use loop_run::Found;

const DTG_VIB: Binary = Binary::new(env!("CARGO_BIN_EXE_dtg-vib")).appending(&["--quiet"]);

/// A hidden rate-gyro term: channel, term id, coefficient.
type Hidden = (&'static str, &'static str, f64);

/// The tri-axial low-frequency vibration test (3–20 Hz on x, y and z, an
/// 8 °C temperature ramp) of `seconds`, with `hidden` on the unit's rate
/// gyros (`temp` as the drift's temperature sensitivity) and nothing else
/// wrong with them.
fn triaxial(seconds: f64, seed: u64, hidden: &[Hidden]) -> Scenario {
    let mut s = Scenario::triaxial_hidden();
    s.name = "unit_hidden".into();
    s.hidden.clear();
    s.duration_s = seconds;
    s.seed = seed;
    for (channel, term, value) in hidden {
        let c = s.unit.rate.entry(channel.to_string()).or_default();
        let t: nav_sensors::rate::RateTerm = term.parse().unwrap();
        c.set(t, *value);
        s.unit.hidden.push(UnitHiddenEffect {
            channel: channel.to_string(),
            term: term.to_string(),
        });
    }
    s
}

/// The vibration test along z (3–20 Hz), the unit standing z up, with the
/// fixture's cross-axis motion on y as an independent drive 10 dB down:
/// a g-sensitivity to y is then not a function of the az windows the
/// network sees (a g² along z would be, and would test nothing).
fn along_z(seconds: f64, seed: u64, hidden: &[Hidden]) -> Scenario {
    let mut s = triaxial(seconds, seed, hidden);
    dtg_vib::demo::shake_along_z(&mut s);
    s
}

/// The loop on a simulated unit with the window these tests were written
/// for: az alone (the library's default chooses among the accelerometers).
fn run(unit: &Unit, s: &Scenario) -> Found {
    loop_run::run(unit, s, Some(&["az"]))
}

/// The id the loop names a hidden term by (`temp` is the record's column).
fn loop_id(term: &str) -> String {
    match term {
        "temp" => "col:temp".into(),
        t => t.into(),
    }
}

/// The acceptance of one unit and seed: exactly the hidden effects, on
/// their channels, intervals covering the truth; nothing on the clean twin;
/// validation rms within 1.1× the clean twin's.
fn accept(unit: &Unit, s: &Scenario, hidden: &[Hidden], clean: &Scenario) {
    let f = run(unit, s);
    let mut want: Vec<(String, String)> = hidden
        .iter()
        .map(|(c, t, _)| (c.to_string(), loop_id(t)))
        .collect();
    let mut got = f.added.clone();
    want.sort();
    got.sort();
    assert_eq!(got, want, "{}: found", unit.name());
    for (c, t, v) in hidden {
        let ci = f.intervals[&(c.to_string(), loop_id(t))];
        assert!(
            ci[0] <= *v && *v <= ci[1],
            "{}: {c}={t}: 95% interval {ci:?} misses {v}",
            unit.name()
        );
    }
    let twin = run(unit, clean);
    assert!(
        twin.added.is_empty(),
        "{}: clean twin: {:?}",
        unit.name(),
        twin.added
    );
    for (k, (a, b)) in f.val_rms.iter().zip(&twin.val_rms).enumerate() {
        assert!(
            *a <= 1.1 * b,
            "{}: channel {k}: refit rms {a} > 1.1 × the clean twin's {b}",
            unit.name()
        );
    }
}

const TETRA: [Hidden; 2] = [("g2", "g_y", 0.5), ("g3", "temp", 0.05)];
const TRIAD: [Hidden; 1] = [("gx", "g_y", 2.0)];
const DUAL: [Hidden; 1] = [("gx2", "g_x", 0.5)];

#[test]
fn tetra_hidden_g_y_and_temperature_are_found_on_their_gyros() {
    let u = Unit::builtin("tetra").unwrap();
    accept(
        &u,
        &triaxial(60.0, 31, &TETRA),
        &TETRA,
        &triaxial(60.0, 31, &[]),
    );
}

#[test]
fn triad_g_y_is_found_on_gx_in_a_z_test_with_cross_axis_motion() {
    let u = Unit::builtin("triad").unwrap();
    accept(
        &u,
        &along_z(60.0, 32, &TRIAD),
        &TRIAD,
        &along_z(60.0, 32, &[]),
    );
}

#[test]
fn dual_triad_g_x_is_found_on_the_second_triad() {
    let u = Unit::builtin("dual-triad").unwrap();
    accept(
        &u,
        &triaxial(60.0, 33, &DUAL),
        &DUAL,
        &triaxial(60.0, 33, &[]),
    );
}

/// The paper's unit with its channels renamed (A…F) and listed in reverse
/// order, its rates in deg/s and specific force in m/s²: the same picks and
/// the same coefficients (deg/h/g inside either way) as the paper's unit.
#[test]
fn the_paper_unit_renamed_reordered_in_deg_s_and_m_s2_gives_the_same_fit() {
    let s = Scenario {
        duration_s: 60.0,
        ..Scenario::triaxial_hidden()
    };
    let paper = Unit::paper();
    let sim = simulate_unit(&paper, &s).unwrap();
    // The paper's unit through the one plug-in, with the options the
    // paper's fit defaults to: the fit chooses its input and prediction
    // smoother (issue 23), the window is az alone.
    let explain_on = |sensor: &UnitSensor, record: &Record| {
        let sig = to_signals(record).unwrap();
        let mut options = sysid::FitOptions::<UnitEffect>::new(6);
        options.recipe.settings.choice = Some(sysid::fit::ModelChoice::default());
        options.recipe.preprocess.window = sysid::WindowSpec::new(vec!["az".into()], 50).unwrap();
        sysid::explain::explain(
            sensor,
            &[("r".into(), &sig)],
            &options,
            &Default::default(),
            5,
            &|_| {},
        )
        .unwrap()
    };
    let today = explain_on(
        &UnitSensor {
            unit: paper.clone(),
            calibration: Some(sim.calibration.clone()),
            rate_reference: RateReference::None,
        },
        &sim.record,
    );
    // The renamed unit: reversed [[gyro]] blocks, names A..F, deg/s and m/s².
    let names = ["X", "X1", "Y", "Y1", "Z", "Z1"];
    let new = ["A", "B", "C", "D", "E", "F"];
    let text = paper.to_toml();
    let (head, blocks) = text.split_once("[[gyro]]").unwrap();
    let (gyros, accels) = blocks.split_once("[[accel]]").unwrap();
    let mut blocks: Vec<String> = gyros.split("[[gyro]]").map(str::to_string).collect();
    for b in blocks.iter_mut() {
        for (o, n) in names.iter().zip(new) {
            *b = b.replace(&format!("name = \"{o}\""), &format!("name = \"{n}\""));
        }
    }
    blocks.reverse();
    // The named residues (after the accelerometers) weigh the gyros by name.
    let mut accels = accels.to_string();
    for (o, n) in names.iter().zip(new) {
        for sep in [" ", "\n"] {
            accels = accels.replace(&format!("{sep}{o} = "), &format!("{sep}{n} = "));
        }
    }
    let renamed_text = format!(
        "{}[[gyro]]{}[[accel]]{accels}",
        head.replace("rate = \"deg/h\"", "rate = \"deg/s\"")
            .replace("specific_force = \"g\"", "specific_force = \"m/s^2\""),
        blocks.join("[[gyro]]"),
    );
    let renamed = Unit::from_toml(&renamed_text, "renamed.toml").unwrap();
    assert_eq!(renamed.gyro_names(), ["F", "E", "D", "C", "B", "A"]);
    assert_eq!(renamed.file_format(), nav_sensors::unit::FileFormat::Unit);
    // The record and calibration in its names, order and units.
    let r = &sim.record;
    let gyros = (0..6)
        .rev()
        .map(|k| (new[k].to_string(), r.gyro_at(k).to_vec()))
        .collect();
    let accels = (0..3)
        .map(|k| (r.accel_names()[k].clone(), r.accel_at(k).to_vec()))
        .collect();
    let extra = r
        .extra_names()
        .iter()
        .map(|n| (n.to_string(), r.extra(n).unwrap().to_vec()))
        .collect();
    let rec = Record::from_series(r.t().to_vec(), gyros, accels, extra, None).unwrap();
    let mut csv = Vec::new();
    rec.write_with_unit(&mut csv, "mem", &renamed).unwrap();
    let read = Record::from_reader_with_unit(csv.as_slice(), "renamed.csv", &renamed).unwrap();
    assert_eq!(read.records.len(), 1);
    let mut cal = UnitCalibration {
        gyros: BTreeMap::new(),
        ..sim.calibration.clone()
    };
    for (o, n) in names.iter().zip(new) {
        cal.gyros.insert(n.to_string(), sim.calibration.gyros[*o]);
    }
    let sensor = UnitSensor {
        unit: renamed.clone(),
        calibration: Some(cal),
        rate_reference: RateReference::None,
    };
    let e = explain_on(&sensor, &read.records[0]);
    for (k, name) in names.iter().enumerate() {
        let p = &today.model.channels()[k];
        let u = &e.model.channels()[5 - k];
        assert_eq!(u.channel(), new[k]);
        let ids = |v: Vec<String>| v;
        assert_eq!(
            ids(p.effects().iter().map(|e| e.id()).collect()),
            ids(u.effects().iter().map(|e| e.id()).collect()),
            "{name}: picks"
        );
        for (a, b) in p.effect_coefficients().iter().zip(u.effect_coefficients()) {
            assert!(
                (a - b).abs() <= 1e-6 * a.abs().max(1e-3),
                "{name}: {a} vs {b}"
            );
        }
        let (a, b) = (p.scores().val_rms, u.scores().val_rms);
        assert!((a - b).abs() <= 1e-6 * a, "{name}: val rms {a} vs {b}");
    }
    assert!(
        today.rounds.iter().any(|r| !r.added.is_empty()),
        "the paper's fit found its hidden effects"
    );
}

/// The command line end to end on a tetra: simulate, explain, then the
/// model's commands with no --unit (the model carries it).
/// `dtg-vib simulate --unit tetra` of `sc` into `dir/sim`.
fn simulate_tetra(dir: &std::path::Path, mut sc: Scenario) -> std::path::PathBuf {
    let scenario = dir.join("tetra.toml");
    sc.name = "tetra".into();
    sc.save(&scenario).unwrap();
    let sim = dir.join("sim");
    let r = DTG_VIB.check(&[
        "simulate",
        "--unit",
        "tetra",
        "--scenario",
        s(&scenario),
        "--out",
        s(&sim),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    sim
}

#[test]
fn the_command_line_runs_the_loop_on_a_tetra() {
    let dir = scratch_dir("dtg-vib-unit-loop");
    let sim = simulate_tetra(dir, triaxial(60.0, 41, &TETRA));
    let record = sim.join("record.csv");
    let calib = sim.join("calibration.json");
    let model = dir.join("m.json");
    let out = DTG_VIB.check(&[
        "explain",
        "--unit",
        "tetra",
        "--data",
        s(&record),
        "--calib",
        s(&calib),
        "--out",
        s(&model),
        // Few centres: the harness allows each run 20 s on a loaded machine.
        "--max-centres",
        "8",
        "--candidates",
        "80",
    ]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("added g2=g_y"), "{}", out.stdout);
    assert!(out.stdout.contains("added g3=col:temp"), "{}", out.stdout);
    let text = std::fs::read_to_string(&model).unwrap();
    assert!(text.contains("\"unit\""), "the model stores its unit");
    for args in [
        vec!["diagnose", "--model", s(&model), "--data", s(&record)],
        vec!["check", "--model", s(&model), "--data", s(&record)],
        vec![
            "residues",
            "--model",
            s(&model),
            "--data",
            s(&record),
            "--out",
            s(&dir.join("res.csv")),
        ],
        vec![
            "compensate",
            "--model",
            s(&model),
            "--data",
            s(&record),
            "--out",
            s(&dir.join("comp.csv")),
        ],
    ] {
        let r = DTG_VIB.check(&args);
        assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
    }
    assert!(
        std::fs::read_to_string(dir.join("res.csv"))
            .unwrap()
            .starts_with("t,P0,P0_pre,P0_comp,P0_out\n")
    );
    // What cannot run on a tetra's model, or does not fit it, is one line:
    // a zero-phase model is not exported (dtg_vib_onboard exports causal
    // models of every built-in unit).
    let e = DTG_VIB.refused(&[
        "export",
        "--model",
        s(&model),
        "--lang",
        "c",
        "--out",
        s(&dir.join("c")),
    ]);
    assert!(e.contains("fit --causal"), "{e}");
    let e = DTG_VIB.refused(&[
        "check",
        "--model",
        s(&model),
        "--unit",
        "triad",
        "--data",
        s(&record),
    ]);
    assert!(e.contains("drop --unit"), "{e}");
    // The model's own unit named again is accepted; a record of another
    // unit is refused naming the missing column.
    let r = DTG_VIB.check(&[
        "check",
        "--model",
        s(&model),
        "--unit",
        "tetra",
        "--data",
        s(&record),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let triad_log = dir.join("triad.csv");
    std::fs::write(
        &triad_log,
        "t,gx,gy,gz,ax,ay,az\n0,0,0,0,0,0,1\n0.02,0,0,0,0,0,1\n",
    )
    .unwrap();
    let e = DTG_VIB.refused(&["check", "--model", s(&model), "--data", s(&triad_log)]);
    assert!(e.contains("no column 'g1' (gyro[0].name"), "{e}");
    // The unit read from the model is named by the model's file.
    assert!(
        e.contains(&format!("the unit stored in {}", model.display())),
        "{e}"
    );
    assert!(!e.contains("<stored unit>"), "{e}");
}

/// Real logs: a moving triad without a rate reference is refused in one
/// line saying why and what would make it observable; a triad has no
/// parity residue; the Allan deviation runs on a still log.
#[test]
fn real_logs_are_read_in_segments_and_refused_where_not_observable() {
    let dir = scratch_dir("dtg-vib-unit-loop");
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/realdata/");
    let handheld = format!("{data}xio_fusion_handheld.csv");
    let e = DTG_VIB.refused(&[
        "fit",
        "--unit",
        "triad",
        "--data",
        &handheld,
        "--out",
        s(&dir.join("x.json")),
    ]);
    assert!(
        e.contains("the unit turns") && e.contains("--table-rate"),
        "{e}"
    );
    let e = DTG_VIB.refused(&[
        "residues",
        "--unit",
        "triad",
        "--data",
        &handheld,
        "--out",
        s(&dir.join("r.csv")),
    ]);
    assert!(e.contains("no parity residue"), "{e}");
    let bench = format!("{data}px4_fmuv4pro_bench.csv");
    let r = DTG_VIB.check(&["allan", "--unit", "triad", "--data", &bench]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("no parity residue"), "{}", r.stdout);
    assert!(r.stderr.contains("gap"), "{}", r.stderr);
    // A bad unit file: the key and the file, in one line.
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        Unit::builtin_toml("triad").unwrap().replacen(
            "input = [1.0, 0.0, 0.0]",
            "input = [0.0, 0.0, 0.0]",
            1,
        ),
    )
    .unwrap();
    let e = DTG_VIB.refused(&["allan", "--unit", s(&bad), "--data", &bench]);
    assert!(e.contains("bad.toml") && e.contains("input"), "{e}");
}

/// A scenario of a duration, seed and hidden effects.
type ScenarioOf = fn(f64, u64, &[Hidden]) -> Scenario;

/// The rates over seeds, per built-in unit: false alarms on clean twins
/// (records with an effect added), power (runs finding exactly the hidden
/// effects), and the 95% intervals' coverage of the truth.
///
/// Measured (20 seeds each, 60-s records, the loop's defaults; the same
/// rates with the worth gate at a 10% and at a 6% cut of the rms):
///
/// | unit | false alarms (clean records with any suggestion) | exactly the hidden effects | 95% intervals covering the truth |
/// |---|---|---|---|
/// | tetra (g2=g_y 0.5, g3=temp 0.05) | 0/20 | 20/20 | 36/40 |
/// | triad (gx=g_y 2.0, z test) | 0/20 | 20/20 | 19/20 |
/// | dual-triad (gx2=g_x 0.5) | 0/20 | 20/20 | 20/20 |
///
/// It asserts each row against the bounds of `assert_rates_within_bounds`.
#[test]
#[ignore = "statistical: 20 seeds per unit (UNIT_LOOP_SEEDS), minutes"]
fn rates_over_seeds() {
    let cases: [(&str, &[Hidden], ScenarioOf); 3] = [
        ("tetra", &TETRA, triaxial),
        ("triad", &TRIAD, along_z),
        ("dual-triad", &DUAL, triaxial),
    ];
    for (name, hidden, scenario) in cases {
        let u = Unit::builtin(name).unwrap();
        let (mut alarms, mut exact, mut covered, mut intervals) = (0, 0, 0, 0);
        let n: u64 = std::env::var("UNIT_LOOP_SEEDS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(20);
        for seed in 0..n {
            let clean = run(&u, &scenario(60.0, 1000 + seed, &[]));
            alarms += usize::from(!clean.added.is_empty());
            let f = run(&u, &scenario(60.0, 1000 + seed, hidden));
            let mut want: Vec<(String, String)> = hidden
                .iter()
                .map(|(c, t, _)| (c.to_string(), loop_id(t)))
                .collect();
            let mut got = f.added.clone();
            want.sort();
            got.sort();
            exact += usize::from(got == want);
            for (c, t, v) in hidden {
                if let Some(ci) = f.intervals.get(&(c.to_string(), loop_id(t))) {
                    intervals += 1;
                    covered += usize::from(ci[0] <= *v && *v <= ci[1]);
                }
            }
        }
        println!(
            "{name}: false alarms {alarms}/{n} clean records, exactly the hidden effects {exact}/{n}, coverage {covered}/{intervals}"
        );
        let expected_intervals = hidden.len() * n as usize;
        assert_rates_within_bounds(
            name,
            n as usize,
            alarms,
            exact,
            (covered, intervals, expected_intervals),
        );
    }
}

/// The bounds the table above is held to, scaled to `n` seeds: at most one
/// clean record in twenty with a suggestion (none at 20 seeds), exactly the
/// hidden effects in at least 19 of 20, and 95% intervals covering the truth
/// at least 90% of the time. Correct 95% intervals fail the coverage bound
/// with probability 4.8% over 40 intervals (binomial P[X ≤ 35] at p = 0.95)
/// and 7.5% over 20 (P[X ≤ 17]); shorter coverage fails it more often.
fn assert_rates_within_bounds(
    name: &str,
    n: usize,
    alarms: usize,
    exact: usize,
    (covered, intervals, expected_intervals): (usize, usize, usize),
) {
    assert!(
        alarms * 20 < n.max(20),
        "{name}: {alarms}/{n} clean records got a suggestion (bound: under 1 in 20)"
    );
    assert!(
        exact * 20 >= n * 19,
        "{name}: exactly the hidden effects in {exact}/{n} runs (bound: 19 in 20)"
    );
    assert!(
        intervals * 20 >= expected_intervals * 19,
        "{name}: {intervals} intervals of {expected_intervals} hidden effects over {n} runs (bound: 19 in 20 found)"
    );
    assert!(
        covered * 10 >= intervals * 9,
        "{name}: 95% intervals covered the truth {covered}/{intervals} times (bound: 90%)"
    );
}

/// A unit's temperature column is in °C whatever it is called (issue 34
/// §4): a tetra log whose temperature column is `board_temp`, with a unit
/// file naming it (`columns.temperature`), fits `col:board_temp` in
/// deg/h/°C, and the model read back says so (its export); the same column
/// in a unit that does not name it is "per unit of board_temp".
#[test]
fn a_units_temperature_column_is_in_celsius_whatever_it_is_called() {
    let dir = scratch_dir("dtg-vib-board-temp");
    let sim = simulate_tetra(dir, triaxial(20.0, 43, &[("g3", "temp", 0.05)]));
    let csv = std::fs::read_to_string(sim.join("record.csv")).unwrap();
    let (header, rows) = csv.split_once('\n').unwrap();
    assert!(header.ends_with(",temp"), "{header}");
    let record = dir.join("board.csv");
    std::fs::write(
        &record,
        format!("{}board_temp\n{rows}", header.trim_end_matches("temp")),
    )
    .unwrap();
    let tetra = Unit::builtin_toml("tetra").unwrap();
    let named = tetra.replace("time = \"t\"", "time = \"t\"\ntemperature = \"board_temp\"");
    assert_ne!(named, tetra);
    let coefficient_unit = |unit_toml: &str, tag: &str| {
        let unit = dir.join(format!("{tag}.toml"));
        std::fs::write(&unit, unit_toml).unwrap();
        let model = dir.join(format!("{tag}.json"));
        let r = DTG_VIB.check(&[
            "fit",
            "--unit",
            s(&unit),
            "--data",
            s(&record),
            "--effects",
            "col:board_temp",
            "--max-centres",
            "2",
            "--json",
            "--out",
            s(&model),
        ]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let u = j["channels"][2]["effect_coefficients"]["col:board_temp"]["unit"].clone();
        let ex = dir.join(format!("{tag}-export"));
        let r = DTG_VIB.check(&[
            "export",
            "--model",
            s(&model),
            "--lang",
            "text",
            "--out",
            s(&ex),
        ]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        let eq = std::fs::read_to_string(ex.join("equations.txt")).unwrap();
        (u, eq)
    };
    let (u, eq) = coefficient_unit(&named, "named");
    assert_eq!(u, "deg/h/°C");
    assert!(eq.contains("deg/h/°C)·LP[col:board_temp]"), "{eq}");
    let (u, _) = coefficient_unit(tetra, "unnamed");
    assert_eq!(u, "deg/h per unit of board_temp");
}
