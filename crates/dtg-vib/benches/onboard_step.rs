//! One onboard step at the size of issue 13: six channels, K = 100 Gaussian
//! centres each, a 50-sample window on three axes (ax, ay, az: 150 inputs),
//! ground calibration, a 4th-order causal low-pass on two effect terms per
//! channel (g_I and gg_IS). The tables are built here with seeded random
//! centres (the cost of a step does not depend on their values).
//!
//! The same model on the statistics input (per axis: current sample, window
//! mean, window rms: 9 inputs) with the 0.1-Hz prediction smoother is
//! measured in the same run, and its step's ratio to the raw window's
//! printed (a ratio taken in one run holds under load; absolute times do not).
//!
//! Measured: the `dtg-onboard` Rust evaluator (criterion), and the exported
//! C compiled with `cc -O2 -std=c99` and timed in the same run by a small
//! harness (median of 1001 batches of 100 steps: a batch short against the
//! scheduler's time slice, so that a loaded machine delays few batches); the
//! ratio C/Rust is printed with the table size, the state size and the flops
//! per step. `ONBOARD_TABLES_DIR=dir` also writes each model's tables there
//! (for a profiler or another evaluator).
//!
//! ```sh
//! CARGO_TARGET_DIR=... cargo bench -p dtg-vib --bench onboard_step
//! ```

use criterion::{Criterion, criterion_group, criterion_main};
use dtg_onboard::{Evaluator, FIXED_HEADER_WORDS, FLAG_CALIBRATION, MAGIC, Model, VERSION, kind};
use dtg_vib::export::{Precision, Tables, c_sources_from_tables};
use dtg_vib::signal::LowPass;
use nav_sensors::geometry::{ChannelFrame, least_squares_operator};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use std::hint::black_box;
use std::process::Command;
use std::time::Duration;

const K: usize = 100;
const L: usize = 50;
const SIGNALS: usize = 3;
const STEPS: usize = 2000;

/// The tables of the benchmark's model on the network input `input`
/// (`dtg_onboard::input`): the raw window has no smoother, the statistics
/// input the 0.1-Hz prediction smoother. With `shared`, every channel has
/// channel X's centres and widths (its own weights), as the fit's one
/// selection for channels sharing an input gives: the kernel values are
/// then computed once per step.
fn tables(input: u32, shared: bool) -> Tables {
    let stats = input == dtg_onboard::input::STATISTICS;
    let smoother = LowPass::butterworth(2, 0.1, 50.0).unwrap();
    let mut rng = Xoshiro256Plus::seed_from_u64(13);
    let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
    let mut words: Vec<u32> = vec![
        u32::from_le_bytes(MAGIC),
        VERSION,
        0,
        FLAG_CALIBRATION,
        0,
        lp.sections().len() as u32,
        0,
        L as u32,
        SIGNALS as u32,
    ];
    words.extend([2u32; 6]);
    words.extend([K as u32; 6]);
    assert_eq!(words.len(), FIXED_HEADER_WORDS);
    words.extend([0, 1, 2]);
    for _ in 0..6 {
        words.extend([kind::LINEAR_G, 0, kind::QUADRATIC_G, 0]);
    }
    words.extend([input, if stats { 1 } else { 0 }]);
    if words.len() % 2 == 1 {
        words.push(0);
    }
    words[2] = words.len() as u32;
    let mut f = vec![0.02];
    let frames = ChannelFrame::all();
    for fr in &frames {
        for v in [fr.input, fr.other, fr.spin] {
            f.extend([v.x, v.y, v.z]);
        }
    }
    let ls = least_squares_operator();
    for i in 0..3 {
        f.extend((0..6).map(|j| ls[(i, j)]));
    }
    for _ in 0..6 {
        // 18 DTG terms (temp and rect_2n zero) and the nonlinearity.
        f.extend((0..16).map(|_| rng.gen_range(-0.5..0.5)));
        f.extend([0.0, 0.0, 0.3]);
    }
    for _ in 0..3 {
        f.extend((0..8).map(|_| rng.gen_range(-50.0..50.0)));
    }
    for (s, z) in lp.sections().iter().zip(lp.steady_state()) {
        f.extend([s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]]);
    }
    if stats {
        for (s, z) in smoother.sections().iter().zip(smoother.steady_state()) {
            f.extend([s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]]);
        }
    }
    let mut first: Option<(Vec<f64>, Vec<f64>)> = None;
    for fr in &frames {
        f.push(rng.gen_range(-5.0..5.0)); // bias
        f.extend([0.8, -0.1]); // g_I, gg_IS coefficients
        f.extend([fr.input.x, fr.input.y, fr.input.z]);
        f.extend([
            fr.input.x, fr.input.y, fr.input.z, fr.spin.x, fr.spin.y, fr.spin.z,
        ]);
        let widths: Vec<f64> = (0..K).map(|_| rng.gen_range(2.0..6.0)).collect();
        let weights: Vec<f64> = (0..K).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut centres = Vec::new();
        for _ in 0..K {
            for s in 0..SIGNALS {
                let g = if s == 2 { 1.0 } else { 0.0 };
                if stats {
                    // Current sample, window mean, window rms.
                    centres.extend([
                        g + rng.gen_range(-0.5..0.5),
                        g + rng.gen_range(-0.05..0.05),
                        rng.gen_range(0.0..0.3),
                    ]);
                } else {
                    centres.extend((0..L).map(|_| g + rng.gen_range(-0.5..0.5)));
                }
            }
        }
        let (widths, centres) = match (&first, shared) {
            (Some((w, c)), true) => (w.clone(), c.clone()),
            _ => (widths, centres),
        };
        first.get_or_insert((widths.clone(), centres.clone()));
        f.extend(widths);
        f.extend(weights);
        f.extend(centres);
    }
    let mut bytes = Vec::new();
    for w in &words {
        bytes.extend(w.to_le_bytes());
    }
    for v in &f {
        bytes.extend(v.to_le_bytes());
    }
    Tables {
        bytes,
        extra: vec![],
    }
}

/// Seeded raw inputs: Earth-rate-like outputs and a vibrating 1 g.
fn inputs() -> Vec<([f64; 6], [f64; 3])> {
    let mut rng = Xoshiro256Plus::seed_from_u64(7);
    (0..STEPS)
        .map(|_| {
            (
                std::array::from_fn(|_| rng.gen_range(-15.0..15.0)),
                [
                    rng.gen_range(-0.3..0.3),
                    rng.gen_range(-0.3..0.3),
                    1.0 + rng.gen_range(-0.3..0.3),
                ],
            )
        })
        .collect()
}

const HARNESS: &str = r#"#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "dtg_model.h"
static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
int main(void) {
    enum { BATCHES = 1001, PER = 100 };
    static double gyro[PER][6], acc[PER][3];
    double times[BATCHES], rate[6], a_out[3], sink = 0;
    dtg_state s;
    int b, i, k;
    unsigned long seed = 7;
    for (i = 0; i < PER; i++) {
        for (k = 0; k < 6; k++) { seed = seed * 6364136223846793005UL + 1; gyro[i][k] = 30.0 * ((seed >> 11) / 9007199254740992.0) - 15.0; }
        for (k = 0; k < 3; k++) { seed = seed * 6364136223846793005UL + 1; acc[i][k] = (k == 2) + 0.6 * ((seed >> 11) / 9007199254740992.0) - 0.3; }
    }
    dtg_init(&s);
    for (i = 0; i < PER; i++) dtg_step(&s, gyro[i], acc[i], 0, rate, a_out);
    for (b = 0; b < BATCHES; b++) {
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (i = 0; i < PER; i++) { dtg_step(&s, gyro[i], acc[i], 0, rate, a_out); sink += rate[0]; }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        times[b] = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / PER;
    }
    qsort(times, BATCHES, sizeof times[0], cmp);
    printf("%.1f %g\n", times[BATCHES / 2], sink);
    return 0;
}
"#;

/// Median ns per step of the exported C of the bench `name`, or why it was
/// not measured (the sources stay in the temporary directory named).
fn c_step_ns(name: &str, t: &Tables, precision: Precision) -> Result<f64, String> {
    let dir = std::env::temp_dir().join(format!(
        "dtg-onboard-bench-{}-{name}-{precision:?}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let c = c_sources_from_tables(t, precision).map_err(|e| e.to_string())?;
    for (name, text) in c.files() {
        if name != "main.c" {
            std::fs::write(dir.join(name), text).map_err(|e| e.to_string())?;
        }
    }
    std::fs::write(dir.join("bench.c"), HARNESS).map_err(|e| e.to_string())?;
    let ok = Command::new("cc")
        .current_dir(&dir)
        .args([
            "-O2",
            "-std=c99",
            "dtg_model.c",
            "bench.c",
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

fn bench(c: &mut Criterion) {
    let data = inputs();
    let mut medians = Vec::new();
    for (name, input, shared) in [
        ("rust_step_k100_w50x3", dtg_onboard::input::RAW, false),
        (
            "rust_step_k100_stats3x3_smoothed",
            dtg_onboard::input::STATISTICS,
            false,
        ),
        (
            "rust_step_k100_stats3x3_smoothed_shared",
            dtg_onboard::input::STATISTICS,
            true,
        ),
    ] {
        let t = tables(input, shared);
        if let Some(dir) = std::env::var_os("ONBOARD_TABLES_DIR") {
            // The tables for a profiler or an evaluator outside this bench.
            std::fs::write(
                std::path::Path::new(&dir).join(format!("{name}.dtgo")),
                &t.bytes,
            )
            .expect("ONBOARD_TABLES_DIR is writable");
        }
        let m = Model::parse(&t.bytes).unwrap();
        let mut state = vec![0.0; m.state_len()];
        let mut ev = Evaluator::new(m, &mut state).unwrap();
        for (g, a) in &data {
            ev.step(g, a, &[]).unwrap();
        }
        let mut i = 0;
        let mut group = c.benchmark_group("onboard");
        group.measurement_time(Duration::from_secs(5));
        group.bench_function(name, |b| {
            b.iter(|| {
                let (g, a) = &data[i % STEPS];
                i += 1;
                black_box(ev.step(black_box(g), black_box(a), &[]).unwrap())
            })
        });
        group.finish();

        let sets = (0..6).filter(|&c| m.centre_set(c) == c).count();
        assert_eq!(
            sets,
            if shared { 1 } else { 6 },
            "the evaluator finds the sets"
        );
        println!(
            "{name}: tables {} bytes (centres {} bytes), state {} f64, {} flops per step",
            m.size_bytes(),
            6 * K * m.input_dim() * 8,
            m.state_len(),
            m.flops_per_step()
        );
        // The Rust median again, outside criterion, in the same units as the
        // C harness (median of 1001 batches of 100 steps), for the ratios.
        let mut times = Vec::new();
        for _ in 0..1001 {
            let t0 = std::time::Instant::now();
            for (g, a) in data.iter().take(100) {
                black_box(ev.step(g, a, &[]).unwrap());
            }
            times.push(t0.elapsed().as_nanos() as f64 / 100.0);
        }
        times.sort_by(f64::total_cmp);
        let rust = times[500];
        println!("{name}: rust evaluator median {rust:.1} ns per step");
        let mut c_ns = Vec::new();
        for p in [Precision::F64, Precision::F32] {
            match c_step_ns(name, &t, p) {
                Ok(ns) => {
                    println!(
                        "{name}: C {p:?} (cc -O2 -std=c99) median {ns:.1} ns per step, {:.2}× the Rust evaluator",
                        ns / rust
                    );
                    c_ns.push(Some(ns));
                }
                Err(e) => {
                    println!("{name}: C {p:?} not measured ({e})");
                    c_ns.push(None);
                }
            }
        }
        medians.push((rust, c_ns));
    }
    let ratio = |what: &str, a: &(f64, Vec<Option<f64>>), b: &(f64, Vec<Option<f64>>)| {
        println!(
            "{what}, same run: Rust {:.3}×{}",
            b.0 / a.0,
            match (a.1[0], b.1[0]) {
                (Some(r), Some(s)) => format!(", C f64 {:.3}×", s / r),
                _ => String::new(),
            }
        );
    };
    let (raw, stats, shared) = (&medians[0], &medians[1], &medians[2]);
    ratio(
        "statistics input + smoother against the raw window",
        raw,
        stats,
    );
    ratio(
        "one centre set for the six channels against six (statistics input)",
        stats,
        shared,
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
