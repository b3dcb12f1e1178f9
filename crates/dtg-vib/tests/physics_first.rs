//! Issue 35 §1: with the default flags (the window's axes chosen from the
//! records), a g-sensitive term the library can state is named, not left
//! inside the network, on records vibrated on three axes.

use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::Channel;
use nav_sensors::sim::{HiddenEffect, Scenario, UnitHiddenEffect};
use nav_sensors::unit::Unit;
mod loop_run;
use loop_run::Found;

/// A hidden term: channel, term id, coefficient.
type Hidden = (&'static str, &'static str, f64);

/// The tri-axial low-frequency vibration test of `seconds` (3–20 Hz on x,
/// y and z), its own hidden terms cleared, with `hidden` set on the unit's
/// gyros: rate-gyro terms in `unit.rate`, DTG terms of the paper's channels
/// in `gyros.channels`.
fn triaxial(seconds: f64, seed: u64, hidden: &[Hidden]) -> Scenario {
    let mut s = Scenario::triaxial_hidden();
    s.name = "physics_first".into();
    for h in std::mem::take(&mut s.hidden) {
        s.gyros
            .channels
            .entry(h.channel)
            .or_default()
            .set(h.term, 0.0);
    }
    s.duration_s = seconds;
    s.seed = seed;
    for (channel, term, value) in hidden {
        match channel.parse::<Channel>() {
            Ok(c) => {
                let t: DtgTerm = term.parse().unwrap();
                s.gyros.channels.entry(c).or_default().set(t, *value);
                s.hidden.push(HiddenEffect {
                    channel: c,
                    term: t,
                });
            }
            Err(_) => {
                let c = s.unit.rate.entry(channel.to_string()).or_default();
                let t: nav_sensors::rate::RateTerm = term.parse().unwrap();
                c.set(t, *value);
                s.unit.hidden.push(UnitHiddenEffect {
                    channel: channel.to_string(),
                    term: term.to_string(),
                });
            }
        }
    }
    s
}

/// Simulates `s` on `unit` and runs the loop with the library's defaults.
fn run(unit: &Unit, s: &Scenario) -> Found {
    loop_run::run(unit, s, None)
}

/// Rates of one hidden term over `seeds` on `unit`, against the clean twins.
#[derive(Debug, Default)]
struct Rates {
    exact: usize,
    covered: usize,
    refit_within: usize,
    seeds: usize,
    /// Each seed's (estimate − truth)/(half-width/1.96) of its 95%
    /// interval, rounded: spread 1 for an interval of the right width.
    z: Vec<f64>,
}

/// The clean twins of `seeds` on `unit`: each one's validation rms, and how
/// many had a suggestion.
fn twins(unit: &Unit, seeds: std::ops::Range<u64>) -> (Vec<Vec<f64>>, usize) {
    let mut rms = Vec::new();
    let mut suggesting = 0;
    for seed in seeds {
        let f = run(unit, &triaxial(SECONDS, seed, &[]));
        if !f.added.is_empty() {
            eprintln!("clean twin seed {seed}: added {:?}", f.added);
            suggesting += 1;
        }
        rms.push(f.val_rms);
    }
    (rms, suggesting)
}

/// Whether the loop's outcome `f` named exactly `h` on exactly its channel,
/// whether its 95 % interval covers the truth, and its z: (estimate −
/// truth)/(half-width/1.96), rounded to 0.001 (spread 1 for an interval of
/// the right width).
fn judged(f: &Found, h: Hidden) -> (bool, bool, Option<f64>) {
    let id = (h.0.to_string(), h.1.to_string());
    let exact = f.added == [id.clone()];
    let interval = f.intervals.get(&id);
    let covered = interval.is_some_and(|[lo, hi]| *lo <= h.2 && h.2 <= *hi);
    let z = interval.map(|[lo, hi]| {
        let z = ((lo + hi) / 2.0 - h.2) / ((hi - lo) / 2.0 / 1.96);
        (z * 1000.0).round() / 1000.0
    });
    (exact, covered, z)
}

/// Exactly `h` named on exactly its channel, its interval covering the
/// truth, the refit within 1.1× its clean twin's validation rms, per seed.
fn rates(unit: &Unit, h: Hidden, seeds: std::ops::Range<u64>, twin_rms: &[Vec<f64>]) -> Rates {
    let mut r = Rates::default();
    for (k, seed) in seeds.enumerate() {
        let f = run(unit, &triaxial(SECONDS, seed, &[h]));
        let (exact, covered, z) = judged(&f, h);
        r.z.extend(z);
        let worst = f
            .val_rms
            .iter()
            .zip(&twin_rms[k])
            .map(|(a, b)| a / b)
            .fold(0.0, f64::max);
        if !exact || !covered || worst > 1.1 {
            eprintln!(
                "{h:?} seed {seed}: added {:?} ci {:?} refit/twin {worst:.3}",
                f.added, f.intervals
            );
        }
        r.exact += usize::from(exact);
        r.covered += usize::from(covered);
        r.refit_within += usize::from(worst <= 1.1);
        r.seeds += 1;
    }
    r
}

/// Record length of every case (s).
const SECONDS: f64 = 60.0;

/// The issue's acceptance on `unit` over seeds 1..=20: 0 of 20 clean twins
/// with a suggestion; per hidden term, exactly it in ≥ 19 of 20 seeds, its
/// 95 % interval covering the truth in ≥ 18 of 20 (a binomial(20, 0.95)
/// falls below 18 with probability 7.5 %), and the refit within 1.1× the
/// clean twin in ≥ 19 of 20.
fn acceptance(unit: &str, cases: &[Hidden]) {
    let unit = Unit::builtin(unit).unwrap();
    let (twin_rms, suggesting) = twins(&unit, 1..21);
    let mut failed = Vec::new();
    for &h in cases {
        let r = rates(&unit, h, 1..21, &twin_rms);
        let rms = (r.z.iter().map(|z| z * z).sum::<f64>() / r.z.len().max(1) as f64).sqrt();
        eprintln!("{h:?}: {r:?}, z rms {rms:.3}");
        if r.exact < 19 || r.covered < 18 || r.refit_within < 19 {
            failed.push((h, r));
        }
    }
    eprintln!("clean twins with a suggestion: {suggesting}/20");
    assert_eq!(suggesting, 0, "clean twins with a suggestion");
    assert!(failed.is_empty(), "below the bounds: {failed:?}");
}

/// Hidden g_x, g_y, g_z and one gg_xy on tetra's rate gyro g2, each below
/// what the network left in its residual before the screen (g_x at 0.15
/// deg/h/g went unnamed in 3 of 3 seeds with the window reading ax, ay, az).
/// Measured (seeds 1–20, 2026-11-29, the seven-mean within-interval
/// covariance and the 6% worth gate; 1766 s at load 5.6 → 16, the DTG
/// test alongside): g_x 20/20 exact, 20/20 covered; g_y 20, 19; g_z 20, 20 (each 20/20 refits within 1.1× the
/// twin); clean twins 0/20; gg_xy at 0.05 deg/h/g² 20/20 exact, 20/20
/// refits within, 17/20 covered. Its regressor is now what the gyro felt
/// (`the_g2_regressor_is_what_the_gyro_felt`; the three-mean quadratic
/// gave 16/20 covered, all four misses above the truth) and the three
/// misses fall on both sides, just outside: seed 2 above (0.0513–0.0661),
/// seeds 11 and 20 below (upper ends 0.0492, 0.0489). Over the 20 seeds
/// gg_xy's z (printed per term) has mean 0.10 and rms 1.13 (g_x, g_y,
/// g_z: rms 0.90, 0.95, 0.92): unbiased, and a spread a
/// 95% interval gives with probability about 0.19 (χ² on 20); 17 of 20
/// or fewer happens to such an interval with probability 7.5%. This test
/// fails on gg_xy's coverage (17 < 18). Over 100 further seeds
/// (`gg_xy_interval_coverage_over_100_seeds`, 2026-11-30, quiet, 179 s)
/// the same interval covers 94 of 100 with z rms 1.021 and mean 0.111, and
/// names gg_xy exactly in 100: the interval is the right width, and seeds
/// 1–20's 17 is the 7.5 % draw, not a bias left to remove.
#[test]
#[ignore = "statistical: 100 loops, minutes"]
fn rate_gyro_g_terms_named_over_seeds() {
    acceptance(
        "tetra",
        &[
            ("g2", "g_x", 0.25),
            ("g2", "g_y", 0.25),
            ("g2", "g_z", 0.25),
            ("g2", "gg_xy", 0.05),
        ],
    );
}

/// Hidden g_S on X and g_O on Y1 of the paper's DTG unit. Measured (seeds
/// 1–20, 2026-11-29, the seven-mean within-interval covariance and the 6%
/// worth gate; 1298 s, load 5.6 → 16): g_S 20/20 exact, 19/20 covered, 20/20 refits
/// within 1.1× the twin; g_O 20, 20, 20; clean twins 0/20.
#[test]
#[ignore = "statistical: 60 loops, minutes"]
fn dtg_g_terms_named_over_seeds() {
    acceptance("paper", &[("X", "g_S", 0.3), ("Y1", "g_O", 0.3)]);
}

/// CI's short version: one seed of a hidden g_x on g2 at 0.25 deg/h/g,
/// named alone with an interval covering it, and its clean twin silent.
#[test]
fn hidden_g_x_named_with_the_default_window() {
    let unit = Unit::builtin("tetra").unwrap();
    let (twin_rms, suggesting) = twins(&unit, 3..4);
    assert_eq!(suggesting, 0);
    let r = rates(&unit, ("g2", "g_x", 0.25), 3..4, &twin_rms);
    assert_eq!((r.exact, r.covered, r.refit_within), (1, 1, 1), "{r:?}");
}

/// The slope of the drift a hidden `term` (coefficient 1) adds to g2's
/// record on the regressor the loop states it with, both low-passed as the
/// loop's targets are (4th order, 5 Hz, zero-phase): 1 when the regressor
/// is what the gyro felt.
fn regressor_slope(unit: &Unit, term: &'static str, seed: u64) -> f64 {
    use dtg_vib::unit_sensor::{RateReference, UnitSensor, to_signals};
    use sysid::Sensor;
    let with =
        nav_sensors::sim::simulate_unit(unit, &triaxial(SECONDS, seed, &[("g2", term, 1.0)]))
            .unwrap();
    let without = nav_sensors::sim::simulate_unit(unit, &triaxial(SECONDS, seed, &[])).unwrap();
    let (a, b) = (
        to_signals(&with.record).unwrap(),
        to_signals(&without.record).unwrap(),
    );
    let drift: Vec<f64> = a
        .column("g2")
        .unwrap()
        .iter()
        .zip(b.column("g2").unwrap())
        .map(|(x, y)| x - y)
        .collect();
    let sensor = UnitSensor {
        unit: unit.clone(),
        calibration: Some(without.calibration.clone()),
        rate_reference: RateReference::None,
    };
    let channel = unit.gyros().iter().position(|g| g.name == "g2").unwrap();
    let effect = sensor.parse_effect(channel, term).unwrap();
    let calibrated = sensor.calibrate(&b).unwrap();
    let r = &sensor.regressors(&calibrated, channel, &[effect]).unwrap()[0];
    let low_pass = |x: &[f64]| {
        let y = iir::LowPass::butterworth(4, 5.0, 50.0)
            .unwrap()
            .filtfilt(x)
            .unwrap();
        let mean = stats::mean(&y);
        y.iter().map(|v| v - mean).collect::<Vec<f64>>()
    };
    let (d, r) = (low_pass(&drift), low_pass(r));
    let dot = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(x, y)| x * y).sum::<f64>();
    dot(&d, &r) / dot(&r, &r)
}

/// A hidden term's regressor is what the gyro felt (issue 35 §1): the
/// drift a hidden `g_x` or `gg_xy` (coefficient 1) adds to g2's record,
/// regressed on the regressor the loop states it with, both low-passed as
/// the loop's targets are, has slope 1 within 0.02 on seeds 1–3. For
/// `gg_xy` the regressor is the record's estimate of each 50-Hz interval's
/// mean of f_x·f_y: the product of the interval means plus the
/// within-interval covariance (`nav_sensors::dtg::within_interval_covariance`,
/// seven means, shared with the ground calibration and the onboard
/// compensator). Measured: g_x 1.0001, 0.9999, 0.9998; gg_xy 0.9997,
/// 0.9978, 0.9994 (a quadratic through three means gave 1.091, 1.099,
/// 1.088: an estimate high before any network, and intervals above the
/// truth). The spread over seeds (standard deviation 0.001) is the
/// regressor's own scale error on a record: 0.00005 deg/h/g² at 0.05,
/// about 1% of gg_xy's standard error (0.004), so an errors-in-variables
/// term would not move its intervals.
#[test]
fn the_g2_regressor_is_what_the_gyro_felt() {
    let unit = Unit::builtin("tetra").unwrap();
    for seed in 1..4 {
        let linear = regressor_slope(&unit, "g_x", seed);
        let product = regressor_slope(&unit, "gg_xy", seed);
        eprintln!("seed {seed}: slope g_x {linear:.4}, gg_xy {product:.4}");
        assert!((linear - 1.0).abs() < 0.02, "g_x: {linear}");
        assert!((product - 1.0).abs() < 0.02, "gg_xy: {product}");
    }
}

/// Issue 35 §1: the library's default window (`FitOptions::new`) and the
/// command line's (`--window-signals auto`, the default) are one: on records
/// vibrated on three axes both read the same signals (ax, ay and az), at
/// the same length, with the same pre-processing otherwise.
#[test]
fn the_library_and_the_command_line_default_to_one_window() {
    use clap::Parser;
    use dtg_vib::commands::fit_args::{FitArgs, FitRecipe};
    use dtg_vib::unit_sensor::to_signals;

    #[derive(Parser)]
    struct Flags {
        #[command(flatten)]
        fit: FitArgs,
    }
    let unit = Unit::builtin("tetra").unwrap();
    let sim = nav_sensors::sim::simulate_unit(&unit, &triaxial(20.0, 1, &[])).unwrap();
    let dir = tempfile::tempdir().unwrap();
    sim.write_dir(dir.path()).unwrap();
    let file = |f: &str| dir.path().join(f).display().to_string();
    let flags = Flags::try_parse_from([
        "fit",
        "--unit",
        "tetra",
        "--data",
        &file("record.csv"),
        "--calib",
        &file("calibration.json"),
        "--out",
        &file("model.json"),
    ])
    .unwrap();
    let cli = FitRecipe::resolve(&flags.fit).unwrap();

    let library = sysid::FitOptions::<dtg_vib::unit_sensor::UnitEffect>::new(unit.gyros().len());
    assert!(library.recipe.preprocess.window.is_auto());
    let (_, record) = &cli.read.records[0];
    let signals = to_signals(record).unwrap();
    let prepared = sysid::Prepared::new_many(
        &cli.sensor,
        &[("r".into(), &signals)],
        &library.recipe.preprocess,
    )
    .unwrap();
    let chosen = prepared.preprocess();
    let cli_pre = &cli.options.recipe.preprocess;
    assert_eq!(cli_pre.window.signals(), ["ax", "ay", "az"]);
    assert_eq!(chosen.window, cli_pre.window);
    assert_eq!(chosen, cli_pre);
}

/// The seeds where the hidden `gg_xy` explains least (11, 13, 20: ERR
/// 0.156–0.169 at p below 10⁻¹²; left unnamed, its refit's validation rms
/// is 1.107, 1.082 and 1.095× the clean twin's; figures of the three-mean
/// within-interval covariance, before the seven-mean one): named exactly, with the
/// refit within 1.1× the twin, and the twins silent. A gate of a 10% cut
/// of the residual rms left it unnamed on all three; the short run of the
/// statistical test above, a minute.
#[test]
#[ignore = "statistical: 6 loops, a minute"]
fn gg_xy_named_where_it_explains_least() {
    let unit = Unit::builtin("tetra").unwrap();
    for seed in [11, 13, 20] {
        let (twin_rms, suggesting) = twins(&unit, seed..seed + 1);
        assert_eq!(suggesting, 0, "seed {seed}");
        let r = rates(&unit, ("g2", "gg_xy", 0.05), seed..seed + 1, &twin_rms);
        assert_eq!((r.exact, r.refit_within), (1, 1), "seed {seed}: {r:?}");
    }
}

/// The coverage of gg_xy's 95 % interval, measured where 20 seeds cannot
/// tell a right interval from a narrow one (17 of 20 or fewer happens to a
/// right one with probability 7.5 %): seeds 21–120, none of them the
/// acceptance's. Asserts ≥ 90 of 100 covered (a binomial(100, 0.95) falls
/// below 90 with probability 1.1 %) and the hidden term named exactly in
/// ≥ 95 of 100.
#[test]
#[ignore = "statistical: 100 loops, two minutes"]
fn gg_xy_interval_coverage_over_100_seeds() {
    let unit = Unit::builtin("tetra").unwrap();
    let h = ("g2", "gg_xy", 0.05);
    let (mut exact, mut covered, mut zs) = (0, 0, Vec::new());
    for seed in 21..121 {
        let (e, c, z) = judged(&run(&unit, &triaxial(SECONDS, seed, &[h])), h);
        if !c {
            eprintln!("seed {seed}: not covered, z {z:?}");
        }
        exact += usize::from(e);
        covered += usize::from(c);
        zs.extend(z);
    }
    let n = zs.len().max(1) as f64;
    let mean = zs.iter().sum::<f64>() / n;
    let rms = (zs.iter().map(|z| z * z).sum::<f64>() / n).sqrt();
    eprintln!(
        "gg_xy over seeds 21-120: exact {exact}, covered {covered}, z mean {mean:.3}, rms {rms:.3}"
    );
    assert!(covered >= 90, "covered {covered} of 100");
    assert!(exact >= 95, "exact {exact} of 100");
}
