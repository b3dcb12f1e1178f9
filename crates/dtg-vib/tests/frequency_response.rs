//! The FIR tap families read as filters (issue 34 §2: the gyro's frequency
//! response to the rate as a delay and a gain per band; issue 35 §2: a
//! dynamic g-sensitivity as a gain per band, with intervals), on a
//! simulated flight of `units/multi-imu.toml`'s three IMUs (nine gyros,
//! 120 Hz, fitted in parity): g1x reads the rate 2 ms late, and g2z has a
//! high-pass g-sensitivity to a2y, h = (20, −20) deg/h/g (0 at 0 Hz,
//! 40 deg/h/g at 60 Hz). Everything else is exact apart from 0.002 deg/s of
//! white gyro noise and 3 m/s² of white vibration on every accelerometer.
//!
//! In parity a channel's target is its output less the unit's least-squares
//! rate, so one gyro's error among the three along its axis shows as 2/3
//! of it on that gyro and −1/3 on each of the other two: the truths below
//! are those parity-seen ones.

use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use std::f64::consts::TAU;
use std::fmt::Write;
use std::path::Path;

mod workspace_cli;
use workspace_cli::dtg_vib;

const FS: f64 = 120.0;
const N: usize = 6000;
const DELAY_S: f64 = 0.002;
/// g2z's g-sensitivity taps on a2y, deg/h/g.
const G_TAPS: [f64; 2] = [20.0, -20.0];
const G: f64 = 9.80665;

/// The unit's rate about `axis`, deg/s: a slow turn and faster manoeuvres
/// up to 20 Hz.
fn rate(t: f64, axis: usize) -> f64 {
    let a = axis as f64;
    [
        (30.0, 0.31 + 0.07 * a, 0.3 * a),
        (6.0, 3.7 + 1.1 * a, 1.0 + a),
        (3.0, 9.3 + 2.3 * a, 2.0),
        (1.5, 17.1 + 3.1 * a, 0.5 * a),
    ]
    .iter()
    .map(|(amp, f, ph)| amp * (TAU * f * t + ph).sin())
    .sum()
}

/// The simulated flight as the unit file's CSV.
fn flight(seed: u64, path: &Path) {
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut normal = move |s: f64| -> f64 {
        let z: f64 = StandardNormal.sample(&mut rng);
        s * z
    };
    let acc: Vec<Vec<f64>> = (0..9)
        .map(|c| {
            let g = if c % 3 == 2 { G } else { 0.0 };
            (0..N).map(|_| g + normal(3.0)).collect()
        })
        .collect();
    let mut out =
        String::from("t,g1x,g1y,g1z,g2x,g2y,g2z,g3x,g3y,g3z,ax,ay,az,a2x,a2y,a2z,a3x,a3y,a3z\n");
    for i in 0..N {
        let t = i as f64 / FS;
        write!(out, "{t:.9}").unwrap();
        for j in 0..9 {
            let tau = if j == 0 { DELAY_S } else { 0.0 };
            let mut v = rate(t - tau, j % 3) + normal(0.002);
            if j == 5 {
                let g_err: f64 = (0..G_TAPS.len())
                    .map(|k| G_TAPS[k] * acc[4][i.saturating_sub(k)] / G)
                    .sum();
                v += g_err / 3600.0;
            }
            write!(out, ",{v:.9}").unwrap();
        }
        for a in &acc {
            write!(out, ",{:.9}", a[i]).unwrap();
        }
        out.push('\n');
    }
    std::fs::write(path, out).unwrap();
}

/// The mean over `band` (64 midpoints) of Σ g_k e^{−i2πf k/FS}.
fn band_mean(g: &[f64], band: [f64; 2]) -> (f64, f64) {
    let (mut re, mut im) = (0.0, 0.0);
    for p in 0..64 {
        let f = band[0] + (band[1] - band[0]) * (p as f64 + 0.5) / 64.0;
        for (k, gk) in g.iter().enumerate() {
            let w = TAU * f * k as f64 / FS;
            re += gk * w.cos() / 64.0;
            im -= gk * w.sin() / 64.0;
        }
    }
    (re, im)
}

/// The delay parity shows on g1x, ms, without noise: its target 2/3 of
/// its error E = ω(t − τ) − ω(t) regressed (with a bias) on five taps of
/// the unit's least-squares rate ω + E/3, which holds a third of g1x's
/// own error; the phase delay of 1 + h over 0–15 Hz.
fn parity_delay_ms() -> f64 {
    let w: Vec<f64> = (0..N).map(|i| rate(i as f64 / FS, 0)).collect();
    let e: Vec<f64> = (0..N)
        .map(|i| rate(i as f64 / FS - DELAY_S, 0) - w[i])
        .collect();
    let r: Vec<f64> = w.iter().zip(&e).map(|(w, e)| w + e / 3.0).collect();
    let rows = N - 10;
    let x = DMatrix::from_fn(rows, 6, |i, k| match k {
        5 => 1.0,
        k => r[i + 10 - k],
    });
    let y = DVector::from_fn(rows, |i, _| 2.0 / 3.0 * e[i + 10]);
    let h = x.svd(true, true).solve(&y, 1e-12).unwrap();
    let mut g: Vec<f64> = (0..5).map(|k| h[k]).collect();
    g[0] += 1.0;
    let (re, im) = band_mean(&g, [0.0, 15.0]);
    -im.atan2(re) / (TAU * 7.5) * 1e3
}

/// g2z's band gains as parity shows them on a gyro of the z group, deg/h/g:
/// `share` (2/3 on g2z, 1/3 on g1z and g3z) of the taps' band gains.
fn parity_gains(share: f64) -> Vec<f64> {
    (0..4)
        .map(|b| {
            let (re, im) = band_mean(&G_TAPS, [15.0 * b as f64, 15.0 * (b + 1) as f64]);
            share * re.hypot(im)
        })
        .collect()
}

fn fit(dir: &Path, seed: u64) -> serde_json::Value {
    fit_with(dir, seed, "sf@0..4,acc:a2y@0..5")
}

/// Simulates seed `seed`'s flight and fits it with `effects` into
/// `m{seed}.json`; the fit's JSON.
fn fit_with(dir: &Path, seed: u64, effects: &str) -> serde_json::Value {
    let data = dir.join(format!("flight{seed}.csv"));
    flight(seed, &data);
    let out = dir.join(format!("m{seed}.json"));
    let o = dtg_vib(&workspace_cli::linear(
        "fit",
        "units/multi-imu.toml",
        data.to_str().unwrap(),
        effects,
        &["--json", "--out", out.to_str().unwrap()],
    ));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// A channel's family in `fit --json`.
fn family<'a>(fitted: &'a serde_json::Value, channel: &str, id: &str) -> &'a serde_json::Value {
    let c = fitted["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["channel"] == channel)
        .unwrap();
    c["frequency_response"]
        .as_array()
        .unwrap_or_else(|| panic!("{channel}: no frequency_response in {c}"))
        .iter()
        .find(|f| f["family"] == id)
        .unwrap()
}

fn covers(c: &serde_json::Value, v: f64) -> bool {
    let ci = c["ci95"].as_array().unwrap();
    ci[0].as_f64().unwrap() <= v && v <= ci[1].as_f64().unwrap()
}

/// What one seed's fit covers: g1x's delay, then g2z's four band gains.
fn coverage(fitted: &serde_json::Value) -> Vec<bool> {
    let delay = &family(fitted, "g1x", "sf")["delay_ms"];
    let bands = family(fitted, "g2z", "acc:a2y")["bands"]
        .as_array()
        .unwrap();
    std::iter::once(covers(delay, parity_delay_ms()))
        .chain(
            bands
                .iter()
                .zip(parity_gains(2.0 / 3.0))
                .map(|(b, g)| covers(&b["gain"], g)),
        )
        .collect()
}

#[test]
fn a_late_gyro_and_a_g_sensitive_one_read_as_filters() {
    let dir = tempfile::tempdir().unwrap();
    let fitted = fit(dir.path(), 1);
    // The truth parity shows is within 1% of 2/3 of the 2 ms (the rest:
    // the least-squares rate holds a third of g1x's own error).
    let truth = parity_delay_ms();
    assert!((truth / (2.0 / 3.0 * 2.0) - 1.0).abs() < 0.01, "{truth}");
    let sf = family(&fitted, "g1x", "sf");
    assert_eq!(sf["lags"], serde_json::json!([0, 1, 2, 3, 4]));
    assert!(
        covers(&sf["delay_ms"], truth),
        "{} vs {truth}",
        sf["delay_ms"]
    );
    // g2z's band gains cover the truth, each band's edges from the 120 Hz
    // rate; the phase is given where the gain is told from zero.
    let a = family(&fitted, "g2z", "acc:a2y");
    assert_eq!(a["unit"], "deg/h/g");
    let bands = a["bands"].as_array().unwrap();
    assert_eq!(bands.len(), 4);
    for (k, (b, g)) in bands.iter().zip(parity_gains(2.0 / 3.0)).enumerate() {
        let hz = b["band_hz"].as_array().unwrap();
        assert!(
            (hz[1].as_f64().unwrap() - 15.0 * (k + 1) as f64).abs() < 1e-6,
            "{b}"
        );
        assert!(covers(&b["gain"], g), "band {k}: {b} vs {g}");
        assert!(b["gain"]["ci95"][0].as_f64().unwrap() > 0.0, "{b}");
        assert!(b["phase_deg"]["value"].is_f64(), "{b}");
    }
    // A gyro of another axis has no such response: every band's interval
    // starts at 0 and no phase is given.
    for b in family(&fitted, "g1y", "acc:a2y")["bands"]
        .as_array()
        .unwrap()
    {
        assert_eq!(b["gain"]["ci95"][0], 0.0, "{b}");
        assert!(b.get("phase_deg").is_none(), "{b}");
    }
    assert_eq!(coverage(&fitted), [true; 5]);
}

/// The diagnosis of a model without the accelerometer taps names g2z's
/// g-sensitivity: an `acc:a2y` tap is suggested on g2z, and on no gyro of
/// the x or y axes (parity shows the z group's error on the z gyros only).
#[test]
fn the_diagnosis_names_the_g_sensitivity() {
    let dir = tempfile::tempdir().unwrap();
    fit_with(dir.path(), 1, "sf@0..4");
    let o = dtg_vib(&[
        "diagnose",
        "--model",
        dir.path().join("m1.json").to_str().unwrap(),
        "--data",
        dir.path().join("flight1.csv").to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let d: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let names_a2y = |c: &serde_json::Value| {
        c["suggested"]
            .as_array()
            .unwrap()
            .iter()
            .any(|e| e.as_str().unwrap().starts_with("acc:a2y"))
    };
    for c in d["channels"].as_array().unwrap() {
        let ch = c["channel"].as_str().unwrap();
        match ch {
            "g2z" => assert!(names_a2y(c), "{ch}: {}", c["suggested"]),
            _ if !ch.ends_with('z') => assert!(!names_a2y(c), "{ch}: {}", c["suggested"]),
            _ => {}
        }
    }
}

/// Over 20 seeds, g1x's delay and each of g2z's four band gains are covered
/// by their 95% intervals in at least 18 (the binomial 1% tail of 95% over
/// 20 is 16; 18 is the bar). `cargo test --release -p dtg-vib
/// --test frequency_response -- --ignored --nocapture` prints the rates.
#[test]
#[ignore = "20 fits of a simulated flight; run by hand (minutes)"]
fn band_gains_and_the_delay_cover_over_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let mut hits = [0usize; 5];
    for seed in 1..=20 {
        for (h, c) in hits.iter_mut().zip(coverage(&fit(dir.path(), seed))) {
            *h += usize::from(c);
        }
    }
    println!(
        "covered of 20: g1x delay {}, g2z band gains 0–15 Hz {}, 15–30 Hz {}, 30–45 Hz {}, 45–60 Hz {}",
        hits[0], hits[1], hits[2], hits[3], hits[4]
    );
    assert!(hits.iter().all(|&h| h >= 18), "{hits:?}");
}
