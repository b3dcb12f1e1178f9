//! Issue 13's acceptance: a causal model, exported as C99 and as tables for
//! the `no_std` evaluator, gives the desktop tool's numbers.
//!
//! The reference is the batch pipeline (calibration, filters, effect columns
//! and the RBF over whole-record arrays, `UnitModel::compensation`); the
//! `dtg-onboard` evaluator runs the same model one sample at a time, and the
//! exported C, compiled with the system compiler, runs it from a CSV.

use dtg_vib::unit_sensor::{UnitModel, to_signals};
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

mod workspace_cli;
use workspace_cli::{bin, ok};

/// deg/h: the bound on every channel and sample.
const EQUAL_DEG_H: f64 = 1e-9;

/// The model file at `path`, through the one reader.
fn load(path: &Path) -> UnitModel {
    UnitModel::load(path).unwrap()
}

fn dir() -> &'static Path {
    cli_support::testing::scratch_dir("dtg-vib-onboard")
}

/// A simulated test with a hidden gg_IS on Y1 and a temperature effect on Z
/// (the record has a `temp` column), simulated once.
fn sim() -> &'static Path {
    static SIM: OnceLock<PathBuf> = OnceLock::new();
    SIM.get_or_init(|| {
        let d = dir().join("sim");
        ok(bin()
            .args(["simulate", "--builtin", "triaxial_hidden", "--out"])
            .arg(&d));
        d
    })
}

/// Fits a causal model with `extra` fit arguments; returns its path.
fn fit(name: &str, extra: &[&str]) -> PathBuf {
    let s = sim();
    let out = dir().join(name);
    ok(bin()
        .args(["fit", "--causal", "--max-centers", "20", "--data"])
        .arg(s.join("record.csv"))
        .arg("--calib")
        .arg(s.join("calibration.json"))
        .args(extra)
        .arg("--out")
        .arg(&out));
    out
}

/// The plain causal model: bias and RBF on 50 samples of az.
fn plain() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| fit("plain.json", &[]))
}

/// A causal model that uses every kind of step: effect terms (g_S on all,
/// gg_IS on Y1), an extra column (temp on Z), two windowed signals and an
/// input low-pass.
fn rich() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        fit(
            "rich.json",
            &[
                "--effects",
                "g_S",
                "--add-effect",
                "Y1=gg_IS",
                "--add-effect",
                "Z=col:temp",
                "--window",
                "20",
                "--window-signals",
                "ay,az",
                "--input-cutoff",
                "10",
            ],
        )
    })
}

/// A causal model on the statistics input (current sample, window mean and
/// rms of ax, ay, az: 9 inputs) with an effect and the prediction smoother.
fn statistics() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        fit(
            "statistics.json",
            &[
                "--effects",
                "g_S",
                "--window-signals",
                "ax,ay,az",
                "--input",
                "statistics",
                "--smoother",
                "0.2",
            ],
        )
    })
}

fn record() -> Record {
    Record::read_csv(sim().join("record.csv")).unwrap()
}

/// The simulated record with its specific force along x shifted by 2 g
/// from sample 2000 to 3500: a stretch outside every model's training range,
/// where the network part fades out and back in.
fn outside_record() -> &'static Path {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| {
        let rec = record();
        let mut acc: Vec<Vec<f64>> = (0..3).map(|k| rec.accel_at(k).to_vec()).collect();
        acc[0][2000..3500].iter_mut().for_each(|v| *v += 2.0);
        let p = dir().join("outside.csv");
        rec.with_accel_series(acc).write_csv(&p).unwrap();
        p
    })
}

/// The simulated record with its vibration on every axis smoothed from
/// sample 3000 to 4500 (a 9-sample moving average of each axis's deviation
/// from its mean over the stretch, scaled back to its rms): the same mean
/// and level, another spectrum (its power moved low), outside by the
/// vibration shape alone (sysid::operating::shape).
fn other_shape_record() -> &'static Path {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| {
        let rec = record();
        let mut acc: Vec<Vec<f64>> = (0..3).map(|k| rec.accel_at(k).to_vec()).collect();
        for a in acc.iter_mut() {
            let part = &mut a[3000..4500];
            let n = part.len() as f64;
            let mean = part.iter().sum::<f64>() / n;
            let d: Vec<f64> = part.iter().map(|v| v - mean).collect();
            let smooth: Vec<f64> = (0..d.len())
                .map(|i| {
                    let w = &d[i.saturating_sub(4)..(i + 5).min(d.len())];
                    w.iter().sum::<f64>() / w.len() as f64
                })
                .collect();
            let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / n).sqrt();
            let k = rms(&d) / rms(&smooth);
            for (v, s) in part.iter_mut().zip(&smooth) {
                *v = mean + k * s;
            }
        }
        let p = dir().join("other-shape.csv");
        rec.with_accel_series(acc).write_csv(&p).unwrap();
        p
    })
}

/// Largest |step − batch| of the predicted errors and compensated rates on
/// the simulated record.
fn step_against_batch(model_path: &Path) -> f64 {
    step_against_batch_on(model_path, &record())
}

/// Largest |step − batch| on `rec`, the batch's network part faded outside
/// the training range as compensation fades it.
fn step_against_batch_on(model_path: &Path, rec: &Record) -> f64 {
    step_against_batch_of(&load(model_path), rec).0
}

/// Largest |step − batch| of `m`'s predicted errors, compensated rates and
/// calibrated specific force on `rec`, and the smallest fade weight the
/// batch saw.
fn step_against_batch_of(m: &UnitModel, rec: &Record) -> (f64, f64) {
    let (mut worst, mut lowest) = (0.0f64, 1.0f64);
    let signals = to_signals(rec).unwrap();
    let prepared = m.inner().prepare(&signals).unwrap();
    let batch = m.compensation(&prepared).unwrap();
    if let Some(w) = m.inner().fade_weights(&prepared).unwrap() {
        lowest = w.weight.iter().fold(lowest, |a, &b| a.min(b));
    }
    let stepped = dtg_vib::onboard::step_record(m, rec).unwrap();
    let first = prepared.first_sample();
    assert_eq!(stepped.first_sample, first);
    for (k, name) in m.unit().gyro_names().iter().enumerate() {
        assert_eq!(stepped.error_deg_h[k].len(), batch[k].len());
        let calibrated = &prepared.calibrated().column(name).unwrap()[first..];
        for (i, (s, b)) in stepped.error_deg_h[k].iter().zip(&batch[k]).enumerate() {
            worst = worst.max((s - b).abs());
            worst = worst.max((stepped.rate_deg_h[k][i] - (calibrated[i] - b)).abs());
        }
    }
    for (k, name) in m.unit().accel_names().iter().enumerate() {
        let calibrated = &prepared.calibrated().column(name).unwrap()[first..];
        for (s, b) in stepped.accel_g[k].iter().zip(calibrated) {
            worst = worst.max((s - b).abs());
        }
    }
    (worst, lowest)
}

#[test]
fn the_no_std_evaluator_equals_the_batch_pipeline() {
    for m in [plain(), rich(), statistics()] {
        let worst = step_against_batch(m);
        eprintln!("{}: largest |step − batch| = {worst:e} deg/h", m.display());
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
    }
}

/// A record about as short as the evaluator's lookahead (2 to 4 samples,
/// the lookahead being 3; a record has at least 2) runs as the batch runs
/// it: the flush gives each
/// held sample its own specific force (the calibrated gyros' g-terms read
/// it), with windows of 1 and 2 samples, where the first output needs the
/// flush; and so does the exported C.
#[test]
fn records_shorter_than_the_lookahead_step_as_the_batch() {
    let full = record();
    for window in ["1", "2"] {
        let path = fit(
            &format!("short-window-{window}.json"),
            &[
                "--window",
                window,
                "--window-signals",
                "az",
                "--effects",
                "g_S",
            ],
        );
        let m = load(&path);
        for n in 2..=4 {
            let short = full.slice(0..n);
            let (worst, _) = step_against_batch_of(&m, &short);
            eprintln!("window {window}, {n} samples: largest |step − batch| = {worst:e}");
            assert!(
                worst <= EQUAL_DEG_H,
                "window {window}, {n} samples: {worst:e}"
            );
            let csv = dir().join(format!("short-{window}-{n}.csv"));
            short.write_csv(&csv).unwrap();
            if n < 2 * window.parse::<usize>().unwrap() {
                // `compensate` needs two windows; its refusal says so and
                // offers no other unit (the model's is the log's).
                let o = bin()
                    .args(["compensate", "--model"])
                    .arg(&path)
                    .arg("--data")
                    .arg(&csv)
                    .arg("--out")
                    .arg(dir().join("refused.csv"))
                    .output()
                    .unwrap();
                let e = String::from_utf8_lossy(&o.stderr);
                assert!(!o.status.success() && e.contains("shorten --window"), "{e}");
                assert!(!e.contains("--unit"), "{e}");
                continue;
            }
            if let Some(worst) = c_against_compensate_on(&path, "f64", &csv) {
                eprintln!("window {window}, {n} samples: largest |C − compensate| = {worst:e}");
                assert!(
                    worst <= EQUAL_DEG_H,
                    "window {window}, {n} samples: C {worst:e}"
                );
            }
        }
    }
}

/// The model at `m`, its batch fade weights on `rec` and the record's first
/// prepared sample (weights are indexed from it).
fn fade_weights(m: &Path, rec: &Record) -> (UnitModel, Vec<f64>, usize) {
    let model = load(m);
    let prepared = model.inner().prepare(&to_signals(rec).unwrap()).unwrap();
    let w = model
        .inner()
        .fade_weights(&prepared)
        .unwrap()
        .expect("a new model has a training range")
        .weight;
    let first = prepared.first_sample();
    (model, w, first)
}

#[test]
fn the_fade_outside_the_training_range_is_the_same_in_batch_and_onboard() {
    let rec = Record::read_csv(outside_record()).unwrap();
    // The statistics model has a prediction smoother: the fade holds the
    // network part before it, in batch, onboard and C alike.
    for m in [plain(), rich(), statistics()] {
        // Guards the comparison: the network must fade out and come back.
        let (model, w, first) = fade_weights(m, &rec);
        assert_eq!(w[100], 1.0, "inside before the shift");
        assert!(
            w[3000 - first] < 1e-3,
            "outside: weight {}",
            w[3000 - first]
        );
        assert_eq!(*w.last().unwrap(), 1.0, "inside again after it");
        let t = dtg_vib::export::tables(&model).unwrap();
        assert!(dtg_onboard::Model::parse(&t.bytes).unwrap().fades());
        let worst = step_against_batch_on(m, &rec);
        eprintln!(
            "{} outside: largest |step − batch| = {worst:e} deg/h",
            m.display()
        );
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
    }
}

/// The fade's vibration shape is one definition in batch, onboard and C:
/// on a stretch of the same mean and level and another spectrum the weight
/// falls (the shape alone sees it) and the three agree.
#[test]
fn the_fade_on_another_spectrum_is_the_same_in_batch_onboard_and_c() {
    let rec = Record::read_csv(other_shape_record()).unwrap();
    for m in [plain(), rich(), statistics()] {
        let (model, w, first) = fade_weights(m, &rec);
        let lowest = w[3200 - first..4400 - first]
            .iter()
            .copied()
            .fold(1.0, f64::min);
        assert!(
            lowest < 1e-3,
            "{}: the shape must fade: {lowest}",
            m.display()
        );
        let t = dtg_vib::export::tables(&model).unwrap();
        assert!(
            dtg_onboard::Model::parse(&t.bytes)
                .unwrap()
                .fades_by_shape()
        );
        let worst = step_against_batch_on(m, &rec);
        assert!(
            worst <= EQUAL_DEG_H,
            "{}: step {worst:e} deg/h",
            m.display()
        );
        if m != statistics()
            && let Some(worst) = c_against_compensate_on(m, "f64", other_shape_record())
        {
            assert!(worst <= EQUAL_DEG_H, "{}: C {worst:e} deg/h", m.display());
        }
    }
}

#[test]
fn the_rich_model_uses_effects_extra_columns_and_two_signals() {
    // Guards the test above: the model must exercise what it claims.
    let model = load(rich());
    let t = dtg_vib::export::tables(&model).unwrap();
    assert_eq!(t.extra, ["temp"]);
    let m = dtg_onboard::Model::parse(&t.bytes).unwrap();
    assert_eq!(m.n_effects(Channel::Y1.index()), 2);
    assert_eq!(m.n_effects(Channel::Z.index()), 2);
    assert_eq!(m.window_len(), 20);
    assert!(model.inner().preprocess().input_filter.is_some());
    assert!(model.inner().sensor().calibration.is_some());
}

#[test]
fn the_statistics_model_reads_nine_inputs() {
    // Guards the tests above: the statistics input is what they step.
    let model = load(statistics());
    let t = dtg_vib::export::tables(&model).unwrap();
    let m = dtg_onboard::Model::parse(&t.bytes).unwrap();
    assert_eq!(m.input_kind(), dtg_onboard::input::STATISTICS);
    assert_eq!(m.input_dim(0), 9);
    assert_eq!(m.n_smoother_sections(), 1);
}

#[test]
fn a_causal_model_never_looks_ahead() {
    // Change the record from sample n on: the batch pipeline's predictions
    // before n − 3 must not move (they would under the zero-phase filter);
    // n − 3 … n − 1 may, through the centred covariance: the three samples
    // of latency.
    let model = load(rich());
    let rec = record();
    let n = 3000;
    let mut acc: Vec<Vec<f64>> = (0..3).map(|k| rec.accel_at(k).to_vec()).collect();
    for a in acc.iter_mut() {
        a[n..].iter_mut().for_each(|v| *v += 0.3);
    }
    let gyro: Vec<Vec<f64>> = (0..6)
        .map(|k| {
            let mut g = rec.gyro_at(k).to_vec();
            g[n..].iter_mut().for_each(|v| *v -= 5.0);
            g
        })
        .collect();
    let changed = rec.with_accel_series(acc).with_gyro_series(gyro);
    let prepare = |r: &Record| model.inner().prepare(&to_signals(r).unwrap()).unwrap();
    let (p0, p1) = (prepare(&rec), prepare(&changed));
    let (a, b) = (
        model.inner().predict(&p0).unwrap(),
        model.inner().predict(&p1).unwrap(),
    );
    let first = p0.first_sample();
    for k in 0..6 {
        let lookahead = dtg_onboard::LOOKAHEAD;
        assert_eq!(
            a[k][..n - lookahead - first],
            b[k][..n - lookahead - first],
            "channel {k}"
        );
        assert_ne!(
            a[k][n - first + 5],
            b[k][n - first + 5],
            "the change must reach channel {k}"
        );
    }
}

#[test]
fn a_zero_phase_model_is_not_exported() {
    let s = sim();
    let out = dir().join("zero_phase.json");
    ok(bin()
        .args(["fit", "--max-centers", "5", "--data"])
        .arg(s.join("record.csv"))
        .arg("--out")
        .arg(&out));
    let model = load(&out);
    let err = dtg_vib::export::tables(&model).unwrap_err();
    assert!(err.to_string().contains("--causal"), "{err}");
    let res = bin()
        .args(["export", "--lang", "c", "--model"])
        .arg(&out)
        .arg("--out")
        .arg(dir())
        .output()
        .unwrap();
    assert!(!res.status.success());
    assert!(String::from_utf8_lossy(&res.stderr).contains("fit --causal"));
}

fn read_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

/// Exports `model` as C with `precision`, compiles it with `cc -O2 -std=c99
/// *.c -lm`, runs it on the record, and returns the largest absolute
/// difference from `dtg-vib compensate` over every channel and sample;
/// `None` where there is no C compiler.
fn c_against_compensate(model: &Path, precision: &str) -> Option<f64> {
    c_against_compensate_on(model, precision, &sim().join("record.csv"))
}

/// [`c_against_compensate`] on the record at `data`.
fn c_against_compensate_on(model: &Path, precision: &str, data: &Path) -> Option<f64> {
    c_against_compensate_scaled(model, precision, data, &|_| 1.0)
}

/// The largest |C − compensate| over every column, each difference times
/// `scale(column)` (a unit's rate columns to deg/h; the rest in their own
/// units, to the same bound).
fn c_against_compensate_scaled(
    model: &Path,
    precision: &str,
    data: &Path,
    scale: &dyn Fn(&str) -> f64,
) -> Option<f64> {
    let cc = c_compiler()?;
    let name = model.file_stem().unwrap().to_str().unwrap();
    let data_name = data.file_stem().unwrap().to_str().unwrap();
    let out = dir().join(format!("c-{name}-{precision}-{data_name}"));
    std::fs::create_dir_all(&out).unwrap();
    ok(bin()
        .args(["export", "--lang", "c", "--precision", precision, "--model"])
        .arg(model)
        .arg("--out")
        .arg(&out));
    let c = compile_and_run(
        &cc,
        &out,
        &["-Wall", "-Wextra", "-pedantic", "-Werror"],
        data,
    );
    let desk = dir().join(format!("compensated-{name}-{data_name}.csv"));
    ok(bin()
        .args(["compensate", "--model"])
        .arg(model)
        .arg("--data")
        .arg(data)
        .arg("--out")
        .arg(&desk));
    let d = read_csv(&std::fs::read_to_string(&desk).unwrap());
    Some(largest_difference(&read_csv(&c), &d, scale))
}

/// The C compiler (`$CC`, else `cc`), or `None` with a notice where there
/// is none.
fn c_compiler() -> Option<String> {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    if Command::new(&cc).arg("--version").output().is_err() {
        eprintln!("NOTICE: no C compiler ('{cc}'): the C equality test is skipped");
        return None;
    }
    Some(cc)
}

/// The C in `dir` compiled with `cc -O2 -std=c99 FLAGS dtg_model.c main.c
/// -lm` and run on the record at `data`: its standard output.
fn compile_and_run(cc: &str, dir: &Path, flags: &[&str], data: &Path) -> String {
    let exe = dir.join("dtg");
    let status = Command::new(cc)
        .current_dir(dir)
        .args(["-O2", "-std=c99"])
        .args(flags)
        .args(["dtg_model.c", "main.c", "-lm", "-o"])
        .arg(&exe)
        .status()
        .unwrap();
    assert!(
        status.success(),
        "the C in {} does not compile",
        dir.display()
    );
    let input = std::fs::File::open(data).unwrap();
    let c = Command::new(&exe)
        .stdin(Stdio::from(input))
        .output()
        .unwrap();
    assert!(c.status.success(), "{}", String::from_utf8_lossy(&c.stderr));
    String::from_utf8(c.stdout).unwrap()
}

/// The largest |a − b| of two CSVs with the same header and rows, each
/// difference times `scale(column)`.
fn largest_difference(
    (ha, ra): &(Vec<String>, Vec<Vec<f64>>),
    (hb, rb): &(Vec<String>, Vec<Vec<f64>>),
    scale: &dyn Fn(&str) -> f64,
) -> f64 {
    assert_eq!(ha, hb);
    assert_eq!(ra.len(), rb.len());
    let scales: Vec<f64> = ha.iter().map(|h| scale(h)).collect();
    let mut worst = 0.0f64;
    for (a, b) in ra.iter().zip(rb) {
        for ((x, y), k) in a.iter().zip(b).zip(&scales) {
            worst = worst.max((x - y).abs() * k);
        }
    }
    worst
}

#[test]
fn the_exported_c_equals_compensate() {
    for m in [plain(), rich(), statistics()] {
        let Some(worst) = c_against_compensate(m, "f64") else {
            return;
        };
        eprintln!(
            "{}: largest |C − compensate| = {worst:e} deg/h",
            m.display()
        );
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
    }
}

/// The unroll hint reaches gcc from 8 on and clang only: gcc 7 and older
/// warn of `#pragma GCC unroll`. Seen through the preprocessor as each
/// compiler's version macros make it.
#[test]
fn the_exported_c_hints_unrolling_only_to_compilers_that_know_the_pragma() {
    let Some(cc) = c_compiler() else {
        return;
    };
    let out = dir().join("c-unroll");
    ok(bin()
        .args(["export", "--lang", "c", "--model"])
        .arg(plain())
        .arg("--out")
        .arg(&out));
    let hints = |macros: &[&str]| {
        let o = Command::new(&cc)
            .current_dir(&out)
            .args(["-E", "-std=c99", "-U__GNUC__", "-U__clang__"])
            .args(macros)
            .arg("dtg_model.c")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout)
            .unwrap()
            .matches("unroll")
            .count()
    };
    assert_eq!(hints(&["-D__GNUC__=7"]), 0);
    assert_eq!(hints(&[]), 0);
    assert!(hints(&["-D__GNUC__=8"]) > 0);
    assert!(hints(&["-D__GNUC__=4", "-D__clang__=1"]) > 0);
}

#[test]
fn the_exported_c_fades_as_compensate_does() {
    for m in [plain(), rich()] {
        let Some(worst) = c_against_compensate_on(m, "f64", outside_record()) else {
            return;
        };
        eprintln!(
            "{} outside: largest |C − compensate| = {worst:e} deg/h",
            m.display()
        );
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
    }
}

#[test]
fn the_f32_export_holds_to_a_thousandth_of_a_degree_per_hour() {
    for m in [plain(), rich(), statistics()] {
        let Some(worst) = c_against_compensate(m, "f32") else {
            return;
        };
        eprintln!(
            "{}: largest |C f32 − compensate| = {worst:e} deg/h",
            m.display()
        );
        assert!(worst <= 1e-3, "{}: {worst:e} deg/h", m.display());
    }
}

#[test]
fn text_export_names_every_part_with_units() {
    let out = ok(bin()
        .args(["export", "--lang", "text", "--model"])
        .arg(rich()));
    for want in [
        "causal",
        "Ground calibration",
        "Butterworth, order 4",
        "section 0: b0 = ",
        "error_Y1 [deg/h] =",
        "deg/h/g²)·LP[gg_IS]",
        "deg/h/°C)·LP[col:temp]",
        "w = ",
        "β = ",
        "## Training range and fade",
        "  ax: mean ",
        "w = one-pole of w₀",
    ] {
        assert!(
            out.contains(want),
            "missing '{want}' in:\n{}",
            &out[..out.len().min(3000)]
        );
    }
}

#[test]
fn every_effect_kind_steps_as_the_batch_computes_it() {
    // A turning table (rates of several deg/s, so the anisoinertia terms are
    // observable) with a vibrating specific force, uncalibrated: every term
    // kind of the tables (linear, quadratic with covariance, rate product)
    // against the batch effect columns.
    use dtg_vib::unit_sensor::{RateReference, UnitEffect, UnitSensor};
    use sysid::Sensor;
    let n = 1200;
    let t: Vec<f64> = (1..=n).map(|i| i as f64 * 0.02).collect();
    let wave = |i: usize, f: f64, p: f64| (f * i as f64 * 0.02 + p).sin();
    let accel: [Vec<f64>; 3] = std::array::from_fn(|k| {
        (0..n)
            .map(|i| {
                0.3 * wave(i, 7.0 + k as f64, 0.3)
                    + 0.1 * wave(i, 31.0, k as f64)
                    + if k == 2 { 1.0 } else { 0.0 }
            })
            .collect()
    });
    let gyro: [Vec<f64>; 6] = {
        let m: Vec<[f64; 6]> = (0..n)
            .map(|i| {
                let w = nalgebra::Vector3::new(
                    7200.0 * wave(i, 0.9, 0.0),
                    5400.0 * wave(i, 1.3, 1.0),
                    3600.0 * wave(i, 0.7, 2.0),
                );
                let mut o = nav_sensors::geometry::ideal_outputs(&w);
                for (k, v) in o.iter_mut().enumerate() {
                    *v += 0.5 * accel[2][i] * accel[0][i]
                        + 0.01 * k as f64
                        + 0.2 * wave(i, 3.0 + k as f64, 0.5);
                }
                o
            })
            .collect();
        std::array::from_fn(|k| m.iter().map(|r| r[k]).collect())
    };
    let rec = Record::new(t, gyro, accel, vec![]).unwrap();
    // The paper's unit, uncalibrated, with the paper's fit defaults (input
    // and smoother chosen) on a causal window of ax and az.
    let sensor = UnitSensor {
        unit: nav_sensors::unit::Unit::paper(),
        calibration: None,
        rate_reference: RateReference::None,
    };
    let mut options = sysid::FitOptions::<UnitEffect>::new(6);
    let pre = &mut options.recipe.preprocess;
    pre.window = sysid::WindowSpec::new(vec!["ax".into(), "az".into()], 8).unwrap();
    pre.causal = true;
    options.recipe.effects = (0..6)
        .map(|k| {
            let ids = "g_O,gg_IS,gg_OO,ai_IO,ai_OS".split(',');
            ids.map(|id| sensor.parse_effect(k, id).unwrap()).collect()
        })
        .collect();
    options.recipe.settings.max_centres = 5;
    options.recipe.settings.choice = Some(sysid::fit::ModelChoice::default());
    let signals = to_signals(&rec).unwrap();
    let fitted = sysid::fit::fit(&sensor, &signals, &options, &|_| {}).unwrap();
    let model = UnitModel::of(fitted);
    let prepared = model.inner().prepare(&signals).unwrap();
    let batch = model.compensation(&prepared).unwrap();
    let stepped = dtg_vib::onboard::step_record(&model, &rec).unwrap();
    let mut worst = 0.0f64;
    for (k, b) in batch.iter().enumerate() {
        for (s, b) in stepped.error_deg_h[k].iter().zip(b) {
            worst = worst.max((s - b).abs());
        }
        // The effects carry weight, so a wrong regressor would show.
        let th = model.inner().channels()[k].effect_coefficients();
        assert!(th.iter().all(|v| v.abs() > 0.0), "{th:?}");
    }
    eprintln!("all effect kinds: largest |step − batch| = {worst:e} deg/h");
    assert!(worst <= EQUAL_DEG_H, "{worst:e} deg/h");
}

#[test]
fn export_usage_errors_are_one_line_with_the_fix() {
    let model = plain();
    for (args, want) in [
        (vec!["--lang", "c"], "--out DIR"),
        (vec!["--lang", "rust"], "use c (C99 sources) or text"),
        (
            vec!["--lang", "c", "--precision", "f16", "--out", "x"],
            "use f64 or f32",
        ),
    ] {
        let out = bin()
            .args(["export", "--model"])
            .arg(model)
            .args(&args)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.starts_with("error: ") && err.contains(want), "{err}");
    }
    // A new output directory is created.
    let new = dir().join("new").join("onboard");
    ok(bin()
        .args(["export", "--lang", "c", "--model"])
        .arg(model)
        .arg("--out")
        .arg(&new));
    for f in ["dtg_model.h", "dtg_model.c", "main.c", "model.dtgo"] {
        assert!(new.join(f).is_file(), "{f}");
    }
}

// Units other than the paper's (issue 22): layout version 3, n channels,
// the unit's calibration and effects, checked against the batch and against
// `dtg-vib compensate --unit` as the paper's models are.

/// The paper's geometry as a unit file in deg/s and m/s² (not the paper's
/// format, so it takes the unit path): DTG channels with their own axes.
fn dtg_unit_file() -> &'static Path {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| {
        let text = nav_sensors::unit::Unit::builtin_toml("paper")
            .unwrap()
            .replace("name = \"paper:", "name = \"paper in deg/s:")
            .replace("rate = \"deg/h\"", "rate = \"deg/s\"")
            .replace("specific_force = \"g\"", "specific_force = \"m/s^2\"");
        let p = dir().join("dtg-deg-s.toml");
        std::fs::write(&p, text).unwrap();
        p
    })
}

/// A simulated test of `unit` (a built-in name or a file) on `builtin`.
fn unit_sim(unit: &str, builtin: &str) -> PathBuf {
    let d = dir().join(format!(
        "sim-{}-{builtin}",
        Path::new(unit).file_stem().unwrap().to_str().unwrap()
    ));
    if !d.join("record.csv").is_file() {
        ok(bin()
            .args(["simulate", "--unit", unit, "--builtin", builtin, "--out"])
            .arg(&d));
    }
    d
}

/// A causal model of `unit` on its simulated `builtin` test, with `extra`
/// fit arguments.
fn unit_fit(name: &str, unit: &str, builtin: &str, extra: &[&str]) -> PathBuf {
    sim_fit(name, unit, builtin, true, extra)
}

/// [`unit_fit`], with the simulation's ground calibration when
/// `calibrated`.
fn sim_fit(name: &str, unit: &str, builtin: &str, calibrated: bool, extra: &[&str]) -> PathBuf {
    let s = unit_sim(unit, builtin);
    let out = dir().join(name);
    let mut fit = bin();
    fit.args(["fit", "--causal", "--max-centers", "20", "--unit", unit])
        .arg("--data")
        .arg(s.join("record.csv"));
    if calibrated {
        fit.arg("--calib").arg(s.join("calibration.json"));
    }
    ok(fit.args(extra).arg("--out").arg(&out));
    out
}

/// tetra: rate-gyro effects (g_y on g2, gg_zz on g1), a temperature column
/// on g3, the raw window of az.
fn tetra() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        unit_fit(
            "tetra.json",
            "tetra",
            "triaxial_hidden",
            &[
                "--add-effect",
                "g2=g_y",
                "--add-effect",
                "g1=gg_zz",
                "--add-effect",
                "g3=col:temp",
            ],
        )
    })
}

/// triad (deg/s and m/s²): an effect, two windowed signals and the input
/// low-pass.
fn triad() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        unit_fit(
            "triad.json",
            "triad",
            "z-axis",
            &[
                "--add-effect",
                "gx=g_y",
                "--window",
                "20",
                "--window-signals",
                "ay,az",
                "--input-cutoff",
                "10",
            ],
        )
    })
}

/// dual-triad: six channels on the statistics input with the prediction
/// smoother and a g² effect.
fn dual_triad() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        unit_fit(
            "dual-triad.json",
            "dual-triad",
            "triaxial_hidden",
            &[
                "--add-effect",
                "gx2=gg_xy",
                "--window-signals",
                "ax,ay,az",
                "--input",
                "statistics",
                "--smoother",
                "0.2",
            ],
        )
    })
}

/// The paper's DTGs as a unit in deg/s: DTG calibration and effects in
/// each channel's own axes.
fn dtg_unit() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        let u = dtg_unit_file().to_str().unwrap();
        unit_fit(
            "dtg-unit.json",
            u,
            "triaxial_hidden",
            &["--effects", "g_S", "--add-effect", "Y1=gg_IS"],
        )
    })
}

/// The nine-gyro unit (three IMUs of rate gyros, one accelerometer triad:
/// tests/fixtures/onboard/nine-gyros.toml) on the statistics input with
/// the prediction smoother and a g effect.
fn nine_gyros() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        unit_fit(
            "nine-gyros.json",
            nine_gyros_file(),
            "z-axis",
            &[
                "--add-effect",
                "gx2=g_y",
                "--window-signals",
                "ax,ay,az",
                "--input",
                "statistics",
                "--smoother",
                "0.2",
            ],
        )
    })
}

/// Two IMUs, each of three rate gyros and its own accelerometer triad
/// (tests/fixtures/onboard/two-imus.toml): by default each gyro's network
/// reads its own IMU's accelerometers, so the channels' windows differ.
/// Fitted without a ground calibration: the onboard tables carry one
/// accelerometer triad's calibration, not one per IMU.
fn two_imus() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        let effect = ["--add-effect", "gx2=g_y"];
        sim_fit("two-imus.json", two_imus_file(), "z-axis", false, &effect)
    })
}

/// A model of the two-IMU unit fitted with its ground calibration (each
/// IMU's accelerometer triad calibrated) is not laid out as tables, which
/// carry one triad's: `export` says so and what to do, and causal
/// `compensate` runs the batch, which calibrates every accelerometer.
#[test]
fn a_calibration_of_several_accelerometer_triads_is_not_exported() {
    let s = unit_sim(two_imus_file(), "z-axis");
    let out = dir().join("two-imus-calibrated.json");
    ok(bin()
        .args(["fit", "--causal", "--max-centers", "10", "--unit"])
        .arg(two_imus_file())
        .arg("--data")
        .arg(s.join("record.csv"))
        .arg("--calib")
        .arg(s.join("calibration.json"))
        .arg("--out")
        .arg(&out));
    let err = dtg_vib::export::tables(&load(&out))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("a calibration of the accelerometers") && err.contains("6 accelerometers"),
        "{err}"
    );
    let res = bin()
        .args(["export", "--lang", "c", "--model"])
        .arg(&out)
        .arg("--out")
        .arg(dir().join("two-imus-calibrated-c"))
        .output()
        .unwrap();
    assert!(!res.status.success());
    assert!(
        String::from_utf8_lossy(&res.stderr).contains("compensate --model"),
        "{}",
        String::from_utf8_lossy(&res.stderr)
    );
    ok(bin()
        .args(["compensate", "--model"])
        .arg(&out)
        .arg("--data")
        .arg(s.join("record.csv"))
        .arg("--out")
        .arg(dir().join("two-imus-calibrated.csv")));
}

/// Three gyros of imu2 and three of no IMU, imu1's accelerometers first
/// in the file (tests/fixtures/onboard/mixed-imus.toml): on the z run the
/// first read az2, the others az1 and az2, and the model's list of window
/// signals keeps the file's order, in which each channel's own list is in
/// order (what the onboard masks need).
fn mixed_imus() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| sim_fit("mixed-imus.json", mixed_imus_file(), "z-axis", false, &[]))
}

fn mixed_imus_file() -> &'static str {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/onboard/mixed-imus.toml"
    )
}

fn two_imus_file() -> &'static str {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/onboard/two-imus.toml"
    )
}

fn nine_gyros_file() -> &'static str {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/onboard/nine-gyros.toml"
    )
}

/// A unit's record with its specific force along x shifted by 2 g (in the
/// log's units) from sample 2000 to 3500: outside the training range.
fn unit_outside(model: &Path, data: &Path) -> PathBuf {
    let m = dtg_vib::unit_sensor::UnitModel::load(model).unwrap();
    let text = std::fs::read_to_string(data).unwrap();
    let col = text
        .lines()
        .next()
        .unwrap()
        .split(',')
        .position(|c| c == m.unit().accels()[0].name)
        .unwrap();
    let shift = 2.0 / m.unit().units().specific_force.to_g();
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if (2001..=3500).contains(&i) {
            let mut cells: Vec<String> = line.split(',').map(String::from).collect();
            cells[col] = (cells[col].parse::<f64>().unwrap() + shift).to_string();
            out.push_str(&cells.join(","));
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    let p = dir().join(format!(
        "outside-{}.csv",
        model.file_stem().unwrap().to_str().unwrap()
    ));
    std::fs::write(&p, out).unwrap();
    p
}

/// Largest |step − batch| of a unit model's predicted errors and
/// compensated rates on the log at `data` (every segment), and the smallest
/// fade weight the batch saw.
fn unit_step_against_batch(model_path: &Path, data: &Path) -> (f64, f64) {
    let m = load(model_path);
    let read = Record::read_with_unit(data, m.unit()).unwrap();
    let (mut worst, mut lowest) = (0.0f64, 1.0f64);
    for rec in &read.records {
        let (w, l) = step_against_batch_of(&m, rec);
        (worst, lowest) = (worst.max(w), lowest.min(l));
    }
    (worst, lowest)
}

fn unit_models() -> [(&'static Path, PathBuf); 7] {
    [
        (nine_gyros(), unit_sim(nine_gyros_file(), "z-axis")),
        (two_imus(), unit_sim(two_imus_file(), "z-axis")),
        (mixed_imus(), unit_sim(mixed_imus_file(), "z-axis")),
        (tetra(), unit_sim("tetra", "triaxial_hidden")),
        (triad(), unit_sim("triad", "z-axis")),
        (dual_triad(), unit_sim("dual-triad", "triaxial_hidden")),
        (
            dtg_unit(),
            unit_sim(dtg_unit_file().to_str().unwrap(), "triaxial_hidden"),
        ),
    ]
}

#[test]
fn the_no_std_evaluator_equals_the_batch_on_every_unit() {
    for (m, sim) in unit_models() {
        let data = sim.join("record.csv");
        let (worst, _) = unit_step_against_batch(m, &data);
        eprintln!("{}: largest |step − batch| = {worst:e} deg/h", m.display());
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
        let out = unit_outside(m, &data);
        let (worst, lowest) = unit_step_against_batch(m, &out);
        eprintln!(
            "{} outside: largest |step − batch| = {worst:e} deg/h, weight down to {lowest}",
            m.display()
        );
        assert!(lowest < 1e-3, "{}: the fade must act", m.display());
        assert!(worst <= EQUAL_DEG_H, "{}: {worst:e} deg/h", m.display());
    }
}

#[test]
fn the_unit_models_exercise_what_they_claim() {
    // Guards the tests above and below.
    use dtg_onboard::{Model, VERSION, gyro, input};
    use dtg_vib::unit_sensor::UnitModel;
    let parsed = |p: &Path| {
        let m = UnitModel::load(p).unwrap();
        let t = dtg_vib::export::tables(&m).unwrap();
        (m, t)
    };
    let (m, t) = parsed(tetra());
    let o = Model::parse(&t.bytes).unwrap();
    assert_eq!((o.version(), o.n_channels(), o.n_accels()), (VERSION, 4, 3));
    assert_eq!(t.extra, ["temp"]);
    assert!(m.inner().sensor().calibration.is_some() && o.fades());
    assert_eq!((o.n_effects(0), o.n_effects(1), o.n_effects(2)), (1, 1, 1));
    let (_, t) = parsed(triad());
    let o = Model::parse(&t.bytes).unwrap();
    assert_eq!(o.log_units(), (3600.0, 1.0 / 9.80665));
    assert_eq!(o.window_len(), 20);
    let (_, t) = parsed(dual_triad());
    let o = Model::parse(&t.bytes).unwrap();
    assert_eq!((o.n_channels(), o.input_kind()), (6, input::STATISTICS));
    assert_eq!(o.n_smoother_sections(), 1);
    let (m, t) = parsed(dtg_unit());
    let o = Model::parse(&t.bytes).unwrap();
    assert!(matches!(
        m.unit().gyros()[0].model,
        nav_sensors::unit::GyroModel::Dtg { .. }
    ));
    assert_eq!(o.n_effects(3), 2);
    let (m, t) = parsed(nine_gyros());
    let o = Model::parse(&t.bytes).unwrap();
    assert_eq!((o.n_channels(), o.n_accels()), (9, 3));
    assert!((0..9).all(|c| o.gyro_model(c) == gyro::RATE));
    assert!(m.inner().sensor().calibration.is_some() && o.fades());
    assert_eq!((o.input_kind(), o.n_effects(3)), (input::STATISTICS, 1));
    // Each gyro's network on its own IMU's accelerometer (the z run
    // vibrates along z): the model's list holds both, each channel's mask
    // its own.
    let (m, t) = parsed(two_imus());
    let o = Model::parse(&t.bytes).unwrap();
    let w = &m.inner().preprocess().window;
    assert_eq!(w.signals(), ["az1", "az2"]);
    assert_eq!(
        (w.signals_of(0), w.signals_of(5)),
        (&["az1".to_string()][..], &["az2".to_string()][..])
    );
    let masks: Vec<u32> = (0..6).map(|c| o.signal_mask(c)).collect();
    assert_eq!(masks, [1, 1, 1, 2, 2, 2]);
    // Gyros of an IMU before gyros of none: the model's list in the unit
    // file's order of accelerometers, not in the order the channels read
    // them first, so the last three channels' (az1, az2) is in order.
    let (m, t) = parsed(mixed_imus());
    let o = Model::parse(&t.bytes).unwrap();
    let w = &m.inner().preprocess().window;
    assert_eq!(w.signals(), ["az1", "az2"]);
    assert_eq!(
        (w.signals_of(0), w.signals_of(5)),
        (&["az2".to_string()][..], w.signals())
    );
    let masks: Vec<u32> = (0..6).map(|c| o.signal_mask(c)).collect();
    assert_eq!(masks, [2, 2, 2, 3, 3, 3]);
}

#[test]
fn the_exported_c_equals_compensate_on_every_unit() {
    for (m, sim) in unit_models() {
        // The logs are in the unit's units: a rate difference in deg/s is
        // 3600 times as much in deg/h; the other columns (time, specific
        // force, temperature) are held to the same bound in their own units.
        let unit = dtg_vib::unit_sensor::UnitModel::load(m).unwrap();
        let to_deg_h = unit.unit().units().rate.to_deg_h();
        let gyros: Vec<String> = unit.unit().gyros().iter().map(|g| g.name.clone()).collect();
        let scale = |column: &str| {
            if gyros.iter().any(|g| g == column) {
                to_deg_h
            } else {
                1.0
            }
        };
        let data = sim.join("record.csv");
        let outside = unit_outside(m, &data);
        for (what, d) in [("", data), (" outside", outside)] {
            let Some(worst) = c_against_compensate_scaled(m, "f64", &d, &scale) else {
                return;
            };
            eprintln!(
                "{}{what}: largest |C − compensate| = {worst:e} (deg/h on the rates)",
                m.display()
            );
            assert!(
                worst <= EQUAL_DEG_H,
                "{}{what}: {worst:e} deg/h",
                m.display()
            );
        }
    }
}

#[test]
fn text_export_of_a_unit_names_its_gyros_models_and_units() {
    let out = ok(bin()
        .args(["export", "--lang", "text", "--model"])
        .arg(triad()));
    for want in [
        "of the unit 'triad",
        "gyros gx, gy, gz (deg/s, times 3600 to deg/h)",
        "gx: rate, input axis",
        "error_gx [deg/h] =",
        "deg/h/g)·LP[g_y]",
        "## Training range and fade",
    ] {
        assert!(
            out.contains(want),
            "missing '{want}' in:\n{}",
            &out[..out.len().min(3000)]
        );
    }
}

// Channels sharing one centre set (issue 25 §1): the evaluator and the C
// compute each kernel value once and weight it per channel.

/// The statistics model with every channel given channel X's network
/// (centres, widths) and weights of its own (X's, scaled and shifted): the
/// model the fit's one selection for channels sharing an input gives.
fn shared() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        let text = std::fs::read_to_string(statistics()).unwrap();
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let channels = v["model"]["channels"].as_array_mut().unwrap();
        let (rbf, width) = (channels[0]["rbf"].clone(), channels[0]["width"].clone());
        for (c, ch) in channels.iter_mut().enumerate().skip(1) {
            let mut r = rbf.clone();
            for w in r["weights"]["data"].as_array_mut().unwrap() {
                let x = w[0].as_f64().unwrap();
                w[0] = serde_json::json!(x * (1.0 + 0.25 * c as f64) - 0.01 * c as f64);
            }
            ch["rbf"] = r;
            ch["width"] = width.clone();
        }
        let p = dir().join("shared.json");
        std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
        p
    })
}

#[test]
fn channels_sharing_a_centre_set_step_and_export_as_the_batch() {
    let model = load(shared());
    let t = dtg_vib::export::tables(&model).unwrap();
    let m = dtg_onboard::Model::parse(&t.bytes).unwrap();
    assert!((0..6).all(|c| m.centre_set(c) == 0), "one set");
    let own = dtg_vib::export::tables(&load(statistics())).unwrap();
    let own = dtg_onboard::Model::parse(&own.bytes).unwrap();
    assert!((0..6).all(|c| own.centre_set(c) == c), "six sets");
    assert!(m.flops_per_step() < own.flops_per_step());
    let c = dtg_vib::export::c_sources(&model, dtg_vib::export::Precision::F64).unwrap();
    assert!(c.source.contains("CENTRE_SET[c] != c"), "the shared C");
    for (what, rec) in [
        ("", record()),
        (" outside", Record::read_csv(outside_record()).unwrap()),
    ] {
        let worst = step_against_batch_on(shared(), &rec);
        eprintln!("shared{what}: largest |step − batch| = {worst:e} deg/h");
        assert!(worst <= EQUAL_DEG_H, "shared{what}: {worst:e} deg/h");
    }
    for data in [sim().join("record.csv"), outside_record().to_path_buf()] {
        let Some(worst) = c_against_compensate_on(shared(), "f64", &data) else {
            return;
        };
        eprintln!("shared: largest |C − compensate| = {worst:e} deg/h");
        assert!(worst <= EQUAL_DEG_H, "shared C: {worst:e} deg/h");
    }
}

// Files written before the one layout (main 5b6a72d, tests/fixtures/legacy:
// the paper's tables of layout 2, a tetra's of layout 3, the C exported
// then, the causal models they came from): the tables and the C run as
// they did, and the models exported now give the numbers `compensate` gave
// then (the fixtures' compensated-causal.csv, deg/h and g).

/// A file of the fixtures written before.
fn legacy(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/legacy")
        .join(path)
}

/// The fixtures' compensated log of the causal model of `dir` (paper, tetra).
fn compensated_then(dir: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    read_csv(&std::fs::read_to_string(legacy(dir).join("compensated-causal.csv")).unwrap())
}

#[test]
fn tables_written_before_load_and_run_as_they_did() {
    use dtg_onboard::{LAYOUT_2, LAYOUT_3, Model};
    for (dir, version) in [("paper", LAYOUT_2), ("tetra", LAYOUT_3)] {
        let bytes = std::fs::read(legacy(dir).join("onboard/model.dtgo")).unwrap();
        let m = Model::parse(&bytes).unwrap();
        assert_eq!((m.version(), m.n_extra()), (version, 0), "{dir}");
        let data = legacy(dir).join("record.csv");
        let rec = if dir == "paper" {
            Record::read_csv(&data).unwrap()
        } else {
            let unit =
                nav_sensors::unit::Unit::resolve(legacy("tetra/unit.toml").to_str().unwrap())
                    .unwrap();
            Record::read_with_unit(&data, &unit)
                .unwrap()
                .records
                .remove(0)
        };
        let t = dtg_vib::onboard::Tables {
            bytes: bytes.clone(),
            extra: vec![],
        };
        let s = dtg_vib::onboard::step_tables(&t, &rec).unwrap();
        // The compensated log: time, the gyros' rates, the accelerations.
        let (_, then) = compensated_then(dir);
        let (n_g, n_a) = (m.n_channels(), m.n_accels());
        assert_eq!(s.rate_deg_h[0].len(), then.len(), "{dir}");
        let mut worst = 0.0f64;
        for (i, row) in then.iter().enumerate() {
            for k in 0..n_g {
                worst = worst.max((s.rate_deg_h[k][i] - row[1 + k]).abs());
            }
            for k in 0..n_a {
                worst = worst.max((s.accel_g[k][i] - row[1 + n_g + k]).abs());
            }
        }
        eprintln!("{dir} tables of layout {version}: largest |now − then| = {worst:e}");
        assert!(worst <= EQUAL_DEG_H, "{dir}: {worst:e}");
    }
}

#[test]
fn c_exported_before_compiles_and_runs_as_it_did() {
    let Some(cc) = c_compiler() else { return };
    for dir in ["paper", "tetra"] {
        let out = self::dir().join(format!("c-then-{dir}"));
        std::fs::create_dir_all(&out).unwrap();
        for f in ["dtg_model.h", "dtg_model.c", "main.c"] {
            std::fs::copy(legacy(dir).join("onboard").join(f), out.join(f)).unwrap();
        }
        let c = compile_and_run(&cc, &out, &[], &legacy(dir).join("record.csv"));
        // The C of then carries then's within-interval covariance (a
        // quadratic through three means): it gives then's numbers.
        let then = read_csv(
            &std::fs::read_to_string(legacy(dir).join("compensated-causal-5b6a72d.csv")).unwrap(),
        );
        let worst = largest_difference(&read_csv(&c), &then, &|_| 1.0);
        eprintln!("{dir}: the C of then, largest |C − compensate then| = {worst:e}");
        assert!(worst <= EQUAL_DEG_H, "{dir}: {worst:e}");
    }
}

#[test]
fn models_written_before_export_to_c_that_gives_their_numbers() {
    let Some(cc) = c_compiler() else { return };
    for (dir, model) in [("paper", "causal-gg_IS.json"), ("tetra", "causal.json")] {
        let out = self::dir().join(format!("c-now-{dir}"));
        ok(bin()
            .args(["export", "--lang", "c", "--model"])
            .arg(legacy(dir).join(model))
            .arg("--out")
            .arg(&out));
        let bytes = std::fs::read(out.join("model.dtgo")).unwrap();
        let m = dtg_onboard::Model::parse(&bytes).unwrap();
        assert_eq!(m.version(), dtg_onboard::VERSION, "{dir}: the one layout");
        let flags = ["-Wall", "-Wextra", "-pedantic", "-Werror"];
        let c = compile_and_run(&cc, &out, &flags, &legacy(dir).join("record.csv"));
        let worst = largest_difference(&read_csv(&c), &compensated_then(dir), &|_| 1.0);
        eprintln!("{dir}: exported now, largest |C − compensate then| = {worst:e}");
        assert!(worst <= EQUAL_DEG_H, "{dir}: {worst:e}");
    }
}
