//! Fault detection on the parity vector, as the page states and runs it:
//! one test per sample of the record as logged and as compensated, at a
//! stated false-alarm probability under white noise of a σ given or read
//! from the record ([`crate::unit_sensor::fdi`]).

use super::inputs::{FdiShown, Parity, ResidueRms};
use crate::report::common::fmt;
use crate::unit_sensor::fdi::{self, SigmaSource};
use crate::unit_sensor::residues_of;
use nav_sensors::unit::Unit;
use plot::Table;

/// The residues' rms and fault detection on gyro series of `unit` (per
/// channel, deg/h, every sample) as logged (`before`) and compensated
/// (`after`): see [`fault_detection`].
pub fn parity_on_samples(
    unit: &Unit,
    before: &[Vec<f64>],
    after: &[Vec<f64>],
    sigma: Option<f64>,
    p_fa: f64,
) -> Parity {
    let (pb, pa) = (residues_of(unit, before), residues_of(unit, after));
    Parity {
        residues: unit
            .residue_names()
            .iter()
            .zip(pb.iter().zip(&pa))
            .map(|(n, (b, a))| ResidueRms {
                name: n.clone(),
                before: stats::rms(b),
                after: Some(stats::rms(a)),
            })
            .collect(),
        fdi: fault_detection(unit, before, after, sigma, p_fa),
    }
}

/// Fault detection on gyro series of `unit` (per channel, deg/h, every
/// sample) as logged (`before`) and compensated (`after`), σ given or read
/// from the parity vectors V·m of `before`, false-alarm probability `p_fa`
/// per sample; `None` for three gyros, or when σ reads as 0 (a record
/// without noise has no threshold: the page shows the residues without
/// the test rather than no page).
fn fault_detection(
    unit: &Unit,
    before: &[Vec<f64>],
    after: &[Vec<f64>],
    sigma: Option<f64>,
    p_fa: f64,
) -> Option<FdiShown> {
    if unit.gyros().len() < 4 {
        return None;
    }
    let (test, setting) = fdi::setting(unit, sigma, p_fa, before).ok()?;
    Some(FdiShown {
        setting,
        found: vec![
            ("as logged".to_string(), fdi::run(unit, &test, before)),
            ("compensated".to_string(), fdi::run(unit, &test, after)),
        ],
    })
}

/// The residues' rms on every sample as logged and compensated: the series
/// fault detection tests.
pub(super) fn table(p: &Parity) -> Table {
    let mut t = Table::new([
        "residue",
        "rms as logged (deg/h)",
        "rms compensated (deg/h)",
    ])
    .caption("Every sample from the model's first full window on: the record as logged, and as compensate writes it (the series fault detection tests).");
    for r in &p.residues {
        t = t.row([
            r.name.clone(),
            fmt(r.before),
            r.after.map_or("—".into(), fmt),
        ]);
    }
    t
}

/// The test as stated, then what it found on each series.
pub(super) fn paragraphs(f: &FdiShown, unit: &Unit) -> Vec<String> {
    let st = &f.setting;
    let mut out = vec![format!(
        "Fault detection: one test per sample, on every sample from the model's first full window on, of the record as logged and as compensate writes it: ‖V·m‖ > {} deg/h (V an orthonormal basis of the left null space of the unit's H), set for a false-alarm probability of {:.0e} per test under white noise of σ = {} deg/h per sample ({}); the library's measured rate at 1e-3 on clean simulated records is 8.4e-4 to 1.02e-3 (nav-sensors test fdi_false_alarm). {}",
        fmt(st.threshold_deg_h),
        st.false_alarm_probability,
        fmt(st.sigma_deg_h),
        match st.sigma_source {
            SigmaSource::Given => "given",
            SigmaSource::Estimated => "read from the record's sample-to-sample parity differences",
        },
        if st.isolation_possible {
            "Isolation: the channel whose column of V best explains the parity vector.".to_string()
        } else {
            format!(
                "Isolation is not possible on this unit ({} gyros, V of {} row(s)): a fault is detected but not placed on one gyro.",
                unit.gyros().len(),
                unit.parity_matrix().nrows()
            )
        }
    )];
    out.extend(
        f.found
            .iter()
            .map(|(what, found)| format!("{}.", fdi::line(what, found, st))),
    );
    out
}
