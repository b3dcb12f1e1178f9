//! One onboard step at the size of issue 13 and of issue 37 §4: K = 100
//! Gaussian centres per channel, ground calibration, a 4th-order causal
//! low-pass on two effect terms per channel (the tables are built here,
//! `onboard_step/model.rs`, with seeded random numbers: a step's cost does
//! not depend on their values).
//!
//! - the paper's six DTG channels on a 50-sample window of ax, ay, az
//!   (150 inputs), on the statistics input (per axis current sample, window
//!   mean, window rms: 9 inputs) with the 0.1-Hz prediction smoother, and
//!   the same with one centre set shared by the six;
//! - a flight unit of nine rate gyros in three IMUs
//!   (tests/fixtures/onboard/three-imus.toml) on the statistics input, each
//!   gyro's network on its own IMU's accelerometers, and the same on the
//!   first IMU's (one list of window signals, what the loop fits today).
//!
//! Measured: the `dtg-onboard` Rust evaluator (criterion, and the median of
//! 1001 batches of 100 steps: a batch short against the scheduler's time
//! slice), and the exported C compiled with `cc -O2 -std=c99` and timed in
//! the same run by a small harness (scripts/onboard-pairs/harness.c, the
//! same batches); beside each, the flops and exponentials per step.
//! Against 5b6a72d, same run: scripts/onboard-pairs.sh.
//!
//! `ONBOARD_TABLES_DIR=dir` also writes each model's tables (`NAME.dtgo`),
//! its flops and exponentials per step (`NAME.cost`), the same model in the
//! layout 5b6a72d wrote (`NAME.then.dtgo`, where that layout holds it) and
//! the exported C (`NAME-c/`) there; with `ONBOARD_TABLES_ONLY=1` nothing
//! is measured.
//!
//! ```sh
//! cargo bench -p dtg-vib --bench onboard_step
//! ```

#[path = "../../../scripts/onboard-pairs/inputs.rs"]
mod inputs;
#[path = "onboard_step/model.rs"]
mod model;

use criterion::{Criterion, criterion_group, criterion_main};
use dtg_onboard::{Evaluator, LAYOUT_2, LAYOUT_3, Model, VERSION};
use dtg_vib::export::{Precision, Tables, c_sources_from_tables};
use inputs::inputs;
use model::Spec;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// The C harness (the pairs script's, in the repository).
const HARNESS: &str = include_str!("../../../scripts/onboard-pairs/harness.c");

/// The bench's models.
fn specs() -> Vec<Spec> {
    let (raw, stats) = (dtg_onboard::input::RAW, dtg_onboard::input::STATISTICS);
    vec![
        model::paper("rust_step_k100_w50x3", raw, false),
        model::paper("rust_step_k100_stats3x3_smoothed", stats, false),
        model::paper("rust_step_k100_stats3x3_smoothed_shared", stats, true),
        model::three_imus("rust_step_nine_gyros_k100_stats_own_imu", true),
        model::three_imus("rust_step_nine_gyros_k100_stats_first_imu", false),
    ]
}

/// Writes `spec`'s tables now and then, and its C, into `dir`.
fn write_tables(spec: &Spec, dir: &Path) -> Result<(), String> {
    let then = if spec.unit.file_format() == nav_sensors::unit::FileFormat::Paper {
        LAYOUT_2
    } else {
        LAYOUT_3
    };
    let now = model::tables(spec, VERSION);
    let err = |e: std::io::Error| e.to_string();
    std::fs::write(dir.join(format!("{}.dtgo", spec.name)), &now).map_err(err)?;
    // The step's cost beside it, for the pairs script's physical floor.
    let m = Model::parse(&now).map_err(|e| e.to_string())?;
    let cost = format!("{} {}\n", m.flops_per_step(), m.exps_per_step());
    std::fs::write(dir.join(format!("{}.cost", spec.name)), cost).map_err(err)?;
    // The model with one list of signals has a layout of then too.
    if spec.masks.iter().all(|&m| m == spec.masks[0]) {
        let t = model::tables(spec, then);
        std::fs::write(dir.join(format!("{}.then.dtgo", spec.name)), t).map_err(err)?;
    }
    let c_dir = dir.join(format!("{}-c", spec.name));
    write_c(spec, &now, Precision::F64, &c_dir)
}

/// The exported C of `bytes` into `dir`.
fn write_c(spec: &Spec, bytes: &[u8], precision: Precision, dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let t = Tables {
        bytes: bytes.to_vec(),
        extra: vec![],
    };
    let c = c_sources_from_tables(&t, &spec.unit, precision).map_err(|e| e.to_string())?;
    for (name, text) in c.files() {
        std::fs::write(dir.join(name), text).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Median ns per step of the exported C of `spec` in `precision`, or why it
/// was not measured (the sources stay in the temporary directory named).
fn c_step_ns(spec: &Spec, bytes: &[u8], precision: Precision) -> Result<f64, String> {
    let dir: PathBuf = std::env::temp_dir().join(format!(
        "dtg-onboard-bench-{}-{}-{precision:?}",
        std::process::id(),
        spec.name
    ));
    write_c(spec, bytes, precision, &dir)?;
    std::fs::write(dir.join("harness.c"), HARNESS).map_err(|e| e.to_string())?;
    let ok = Command::new("cc")
        .current_dir(&dir)
        .args([
            "-O2",
            "-std=c99",
            "dtg_model.c",
            "harness.c",
            "-lm",
            "-o",
            "bench",
        ])
        .status()
        .map_err(|e| format!("no C compiler: {e}"))?;
    if !ok.success() {
        return Err("the C does not compile".into());
    }
    let out = Command::new(dir.join("bench"))
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout);
    text.split_whitespace()
        .next()
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| format!("unreadable harness output '{text}'"))
}

/// One model: criterion's figure, then the Rust and C medians of batches
/// and the step's cost; returns the Rust and C f64 medians.
fn measure(c: &mut Criterion, spec: &Spec) -> (f64, Option<f64>) {
    let bytes = model::tables(spec, VERSION);
    let m = Model::parse(&bytes).expect("the bench's tables");
    let data = inputs(m.n_channels(), m.n_accels());
    let mut state = vec![0.0; m.state_len()];
    let mut ev = Evaluator::new(m, &mut state).expect("state");
    for (g, a) in &data {
        ev.step(g, a, &[]).expect("a step");
    }
    let mut i = 0;
    let mut group = c.benchmark_group("onboard");
    group.measurement_time(Duration::from_secs(5));
    group.bench_function(spec.name, |b| {
        b.iter(|| {
            let (g, a) = &data[i % data.len()];
            i += 1;
            black_box(ev.step(black_box(g), black_box(a), &[]).expect("a step"))
        })
    });
    group.finish();
    println!(
        "{}: tables {} bytes, state {} f64, {} flops and {} exponentials per step",
        spec.name,
        m.size_bytes(),
        m.state_len(),
        m.flops_per_step(),
        m.exps_per_step()
    );
    // The Rust median again, outside criterion, in the same units as the
    // C harness (median of 1001 batches of 100 steps), for the ratios.
    let mut times = Vec::new();
    for _ in 0..1001 {
        let t0 = std::time::Instant::now();
        for (g, a) in &data {
            black_box(ev.step(g, a, &[]).expect("a step"));
        }
        times.push(t0.elapsed().as_nanos() as f64 / data.len() as f64);
    }
    times.sort_by(f64::total_cmp);
    let rust = times[500];
    println!("{}: rust evaluator median {rust:.1} ns per step", spec.name);
    let mut c64 = None;
    for p in [Precision::F64, Precision::F32] {
        match c_step_ns(spec, &bytes, p) {
            Ok(ns) => {
                println!(
                    "{}: C {p:?} (cc -O2 -std=c99) median {ns:.1} ns per step, {:.2}× the Rust evaluator",
                    spec.name,
                    ns / rust
                );
                if p == Precision::F64 {
                    c64 = Some(ns);
                }
            }
            Err(e) => println!("{}: C {p:?} not measured ({e})", spec.name),
        }
    }
    (rust, c64)
}

fn bench(c: &mut Criterion) {
    if let Some(dir) = std::env::var_os("ONBOARD_TABLES_DIR") {
        let dir = PathBuf::from(dir);
        std::fs::create_dir_all(&dir).expect("ONBOARD_TABLES_DIR can be made");
        for spec in specs() {
            write_tables(&spec, &dir).expect("ONBOARD_TABLES_DIR is writable");
        }
        if std::env::var_os("ONBOARD_TABLES_ONLY").is_some() {
            return;
        }
    }
    let medians: Vec<(f64, Option<f64>)> = specs().iter().map(|s| measure(c, s)).collect();
    let ratio = |what: &str, a: &(f64, Option<f64>), b: &(f64, Option<f64>)| {
        println!(
            "{what}, same run: Rust {:.3}×{}",
            b.0 / a.0,
            match (a.1, b.1) {
                (Some(r), Some(s)) => format!(", C f64 {:.3}×", s / r),
                _ => String::new(),
            }
        );
    };
    ratio(
        "statistics input + smoother against the raw window",
        &medians[0],
        &medians[1],
    );
    ratio(
        "one centre set for the six channels against six (statistics input)",
        &medians[1],
        &medians[2],
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
