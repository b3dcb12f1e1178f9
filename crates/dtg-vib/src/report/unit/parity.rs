//! Section "Parity residues": P0, P1, … (V·m, V from the unit's H) before
//! and after, and fault detection and isolation on them; or, for a unit of
//! three gyros, that there is none and that its channels are judged
//! against the rate reference.

use super::UnitReport;
use super::channels::change;
use crate::report::common::fmt;
use crate::unit_sensor::fdi::line;
use plot::{Section, Table};

/// The page's sentence on the residues.
pub(super) fn summary(r: &UnitReport<'_>) -> String {
    if r.residues.is_empty() {
        return no_residue(r);
    }
    let each: Vec<String> = r
        .residues
        .iter()
        .map(|p| match p.after {
            Some(a) => format!("{} {} → {}", p.name, fmt(p.before), fmt(a)),
            None => format!("{} {}", p.name, fmt(p.before)),
        })
        .collect();
    let mut s = format!(
        "Parity residues (V·m, every sample, deg/h): {}.",
        each.join("; ")
    );
    if let Some(f) = &r.fdi
        && let Some((what, last)) = f.found.last()
    {
        s.push(' ');
        s.push_str(&line(what, last, &f.setting));
        s.push('.');
    }
    s
}

fn no_residue(r: &UnitReport<'_>) -> String {
    format!(
        "The unit has {} gyros: nothing is redundant, so it has no parity residue and no fault detection; its channels are judged against the rate reference (the channel table).",
        r.unit.gyros().len()
    )
}

/// The section.
pub(super) fn section(r: &UnitReport<'_>) -> Section {
    let s = Section::new("Parity residues");
    if r.residues.is_empty() {
        return s.text(no_residue(r));
    }
    let mut t = Table::new(["residue", "rms before (deg/h)", "rms after (deg/h)", "change"])
        .caption("Every sample from the model's first full window on: before is the record as logged, after as compensate writes it.");
    for p in &r.residues {
        t = t.row([
            p.name.clone(),
            fmt(p.before),
            p.after.map_or("—".into(), fmt),
            p.after.map_or("—".into(), |a| change(p.before, a)),
        ]);
    }
    let mut s = s.table(t).text(format!(
        "The residues are V·m, V an orthonormal basis of the left null space of the unit's H ({} rows from the gyros' input axes): the rate does not enter them, so what they show is the gyros' own error.",
        r.unit.gyros().len()
    ));
    if let Some(f) = &r.fdi {
        let st = &f.setting;
        s = s.text(format!(
            "Fault detection: one test per sample, ‖p‖ > {} deg/h, set for a false-alarm probability of {:.0e} per test under white noise of σ = {} deg/h per sample ({}); the library's measured rate at 1e-3 on clean simulated records is 8.4e-4 to 1.02e-3 (nav-sensors test fdi_false_alarm). {}",
            fmt(st.threshold_deg_h),
            st.false_alarm_probability,
            fmt(st.sigma_deg_h),
            match st.sigma_source {
                crate::unit_sensor::fdi::SigmaSource::Given => "given",
                crate::unit_sensor::fdi::SigmaSource::Estimated => "read from the record's sample-to-sample parity differences",
            },
            if st.isolation_possible {
                "Isolation: the channel whose column of V best explains p."
            } else {
                "Four gyros detect a fault but cannot tell which gyro it is (V has one row)."
            }
        ));
        for (what, found) in &f.found {
            s = s.text(line(what, found, st));
        }
    }
    s
}
