//! The real IMU recordings in `data/realdata/` (provenance and licences in
//! its README.md and LICENSES.md), read with the built-in `triad` unit: the
//! gap counts and largest gaps of the README's table, the sample rates, and
//! the Allan deviation of the two still recordings.
//!
//! `cargo test --release -p nav-sensors --test realdata -- --nocapture`
//! prints what each recording gives.

use nav_sensors::noise::{AllanCurve, NoiseTerm, NoiseTerms};
use nav_sensors::record::{Record, UnitRecords};
use nav_sensors::unit::Unit;

fn read(file: &str) -> UnitRecords {
    let path = format!("{}/../../data/realdata/{file}", env!("CARGO_MANIFEST_DIR"));
    Record::read_with_unit(&path, &Unit::builtin("triad").unwrap())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The README's table: file, rate (Hz), gaps (step > 3 × median), largest
/// gap (ms, as rounded there), whether a temperature column is present.
const TABLE: [(&str, f64, usize, f64, bool); 4] = [
    ("px4_auav_x21_handheld.csv", 250.0, 8, 65.0, false),
    ("px4_fmuv4pro_bench.csv", 250.0, 1, 16.0, true),
    ("px4_cubeorange_vtol_ground.csv", 200.0, 1, 161.0, true),
    ("xio_fusion_handheld.csv", 100.0, 7, 30.0, false),
];

#[test]
fn every_recording_reads_with_the_triad_unit_and_its_gaps_agree_with_the_readme() {
    for (file, rate_hz, gaps, largest_ms, temp) in TABLE {
        let r = read(file);
        eprintln!("{file}: {}", r.time);
        assert_eq!(r.time.gaps.len(), gaps, "{file}");
        let largest = r.time.largest_gap_s().unwrap() * 1000.0;
        assert!((largest - largest_ms).abs() < 0.5, "{file}: {largest} ms");
        // The README's nominal rate, within 3% (the x-io logs at 99.2 Hz).
        assert!(
            (r.time.median_step_s * rate_hz - 1.0).abs() < 0.03,
            "{file}"
        );
        // A gap next to the first or last row leaves an isolated sample, dropped.
        assert_eq!(
            r.records.len() + r.time.dropped_samples.min(gaps),
            gaps + 1,
            "{file}"
        );
        let rows: usize = r.records.iter().map(|s| s.len()).sum::<usize>() + r.time.dropped_samples;
        let lines = std::fs::read_to_string(format!(
            "{}/../../data/realdata/{file}",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap()
        .lines()
        .count();
        assert_eq!(rows, lines - 1, "{file}: every row in one segment");
        for seg in &r.records {
            assert_eq!(seg.extra("temp").is_some(), temp, "{file}");
            // Specific force in g: a unit at rest or moved by hand reads about 1 g.
            let i = seg.len() / 2;
            let f =
                nalgebra::Vector3::new(seg.accel_at(0)[i], seg.accel_at(1)[i], seg.accel_at(2)[i]);
            assert!((f.norm() - 1.0).abs() < 0.5, "{file}: |f| = {} g", f.norm());
        }
    }
}

/// The Allan deviation of each gyro of a still recording's longest segment,
/// and the noise terms read from it.
fn allan(file: &str) -> Vec<(String, NoiseTerms, AllanCurve)> {
    let r = read(file);
    let seg = r.records.iter().max_by_key(|s| s.len()).unwrap();
    seg.gyro_names()
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let curve = AllanCurve::octaves(seg.gyro_at(k), seg.dt(), 0.683)
                .unwrap_or_else(|e| panic!("{file}/{name}: {e}"));
            (name.clone(), NoiseTerms::fit(&curve), curve)
        })
        .collect()
}

fn show(t: &NoiseTerm) -> String {
    match t {
        NoiseTerm::Resolved(e) => format!(
            "{:.4} ({:.4} to {:.4}, τ {}–{} s)",
            e.value, e.low, e.high, e.tau_from_s, e.tau_to_s
        ),
        NoiseTerm::Unresolved {
            reason,
            upper_bound,
        } => {
            format!(
                "unresolved, ≤ {:?}: {reason}",
                upper_bound.map(|b| (b * 1e4).round() / 1e4)
            )
        }
    }
}

#[test]
fn allan_deviation_runs_on_the_still_recordings() {
    for file in ["px4_fmuv4pro_bench.csv", "px4_cubeorange_vtol_ground.csv"] {
        for (name, terms, curve) in allan(file) {
            let adev = curve.adev();
            eprintln!(
                "{file} {name}: ADEV {:.1} deg/h at τ = {:.4} s … {:.1} deg/h at τ = {:.2} s; ARW (deg/√h) {}; bias instability (deg/h) {}",
                adev[0],
                curve.tau_s()[0],
                adev[adev.len() - 1],
                curve.tau_s()[adev.len() - 1],
                show(&terms.arw),
                show(&terms.bias_instability)
            );
            assert!(
                adev.iter().all(|a| a.is_finite() && *a > 0.0),
                "{file}/{name}"
            );
            // A MEMS gyro's noise at the shortest τ: between 1 and 10⁴ deg/h
            // (0.0003 to 3 deg/s), not a unit mix-up by 3600.
            assert!(adev[0] > 1.0 && adev[0] < 1e4, "{file}/{name}: {}", adev[0]);
            if let Some(e) = terms.arw.estimate() {
                assert!(e.low <= e.value && e.value <= e.high);
            }
        }
    }
}
