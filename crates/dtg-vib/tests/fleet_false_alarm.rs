//! How often "out of family" names a unit of a lot that has no outlier.
//!
//! The rule ([`dtg_vib::fleet::family`]: robust z beyond 5 and the unit's
//! 95% interval excluding the lot's median, over 10 units or more) on
//! simulated clean lots: each unit's true coefficient drawn from the lot's
//! normal spread, its estimate off by its own standard error (the loop's
//! intervals are ±1.96 SE), for lots of 10, 20 and 50 units and standard
//! errors from a quarter of the lot's spread (the acceptance lot's: SE
//! ≈ 0.012 deg/h/g against σ 0.05) to four times it, some units measured
//! three times worse than the rest. docs/campaign.md states the bounds
//! asserted here: at most 5% of clean lots of 10 units, 2% of 20 and 1% of
//! 50 name any unit; at most 0.5% of clean units are named.
//!
//! `cargo test --release -p dtg-vib --test fleet_false_alarm -- --ignored`
//! runs 20,000 lots per case and prints the rates; the short version (CI)
//! runs 2,000 lots of 20 units and asserts the bound plus three standard
//! errors of its own count. `clean_lots_through_the_loop` (ignored) runs
//! clean simulated lots through the whole loop (`fleet run`, `fleet
//! summary`) and asserts that the count it names is within what the bound
//! allows.

mod fleet_common;

use dtg_vib::fleet::family::{DEFAULT_THRESHOLD, MIN_UNITS, family};
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

/// The bound on the share of clean lots of `n` units that name any unit.
fn lot_bound(n: usize) -> f64 {
    match n {
        ..=10 => 0.05,
        11..=20 => 0.02,
        _ => 0.01,
    }
}

/// The bound on the share of clean units named.
const UNIT_BOUND: f64 = 0.005;

/// Shares of lots naming anyone and of units named, over `lots` clean lots.
fn rates(n: usize, se_over_spread: f64, lots: usize, seed: u64) -> (f64, f64) {
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
    let unit = Normal::new(0.5, 0.05).unwrap();
    let std = Normal::new(0.0, 1.0).unwrap();
    let (mut lots_named, mut units_named) = (0usize, 0usize);
    for _ in 0..lots {
        let mut values = Vec::with_capacity(n);
        let mut ci = Vec::with_capacity(n);
        for _ in 0..n {
            // One unit in five measured three times worse.
            let se = 0.05 * se_over_spread * if rng.gen_bool(0.2) { 3.0 } else { 1.0 };
            let x = unit.sample(&mut rng) + se * std.sample(&mut rng);
            values.push(x);
            ci.push([x - 1.96 * se, x + 1.96 * se]);
        }
        let f = family(&values, &ci, DEFAULT_THRESHOLD, MIN_UNITS).expect("enough units");
        let named = f.out.iter().filter(|&&o| o).count();
        units_named += named;
        lots_named += usize::from(named > 0);
    }
    (
        lots_named as f64 / lots as f64,
        units_named as f64 / (lots * n) as f64,
    )
}

#[test]
fn out_of_family_on_clean_lots_of_20_stays_within_its_bound() {
    let lots = 2000;
    for (k, ratio) in [0.25, 1.0, 4.0].into_iter().enumerate() {
        let (lot, unit) = rates(20, ratio, lots, 100 + k as u64);
        let b = lot_bound(20);
        let allowance = 3.0 * (b * (1.0 - b) / lots as f64).sqrt();
        assert!(
            lot <= b + allowance,
            "SE/σ {ratio}: {lot} of clean lots named a unit (bound {b})"
        );
        assert!(
            unit <= UNIT_BOUND,
            "SE/σ {ratio}: {unit} of clean units named"
        );
    }
}

#[test]
#[ignore = "statistical: 20,000 lots per case (a few seconds); prints the rates docs/campaign.md quotes"]
fn out_of_family_false_alarm_rates() {
    let lots = 20_000;
    println!("units  SE/σ  lots naming anyone  units named  (bound: lots, units)");
    for n in [10, 20, 50] {
        for (k, ratio) in [0.25, 1.0, 4.0].into_iter().enumerate() {
            let (lot, unit) = rates(n, ratio, lots, 1000 * n as u64 + k as u64);
            println!(
                "{n:>5}  {ratio:>4}  {:>18.2}%  {:>10.3}%  ({:.0}%, {:.1}%)",
                100.0 * lot,
                100.0 * unit,
                100.0 * lot_bound(n),
                100.0 * UNIT_BOUND
            );
            assert!(lot <= lot_bound(n), "{n} units, SE/σ {ratio}: {lot}");
            assert!(unit <= UNIT_BOUND, "{n} units, SE/σ {ratio}: {unit}");
        }
    }
}

#[test]
#[ignore = "statistical, through the whole loop: 4 clean lots of 20 tetra units (minutes on 2 cores)"]
fn clean_lots_through_the_loop() {
    let tmp = tempfile::tempdir().unwrap();
    let (lots, n) = (4usize, 20usize);
    let mut named = 0;
    for l in 0..lots {
        let dir = tmp.path().join(format!("lot{l}"));
        // Each lot its own draws and tests.
        let design = fleet_common::lot_seeded(&dir, n, &[], &[], 20.0, "", 1000 + 100 * l as u64);
        let out = tmp.path().join(format!("out{l}"));
        let r = fleet_common::dtg(&[
            "--quiet",
            "fleet",
            "run",
            "--manifest",
            design.manifest.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(r.status.success(), "{}", fleet_common::text(&r));
        let s = fleet_common::summary(&out);
        let k = s["out_of_family"].as_array().unwrap().len();
        println!("clean lot {l}: {k} of {n} units named out of family");
        named += k;
    }
    // At most UNIT_BOUND of the 80 clean units: 0.4 expected at the bound;
    // more than 2 has a chance below 1% there.
    assert!(
        named <= 2,
        "{named} clean units named out of family in {lots} lots of {n}"
    );
}
