//! `demo --unit`: the demo's loop on any unit ([`dtg_vib::unit_demo`]),
//! and what it prints: what was hidden, what the loop found with its 95%
//! intervals, each channel's rms before and after, the residues with
//! fault detection, and where the pages are.

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::unit_demo::found_text;
use nav_sensors::unit::Unit;
use std::path::Path;

/// Runs the demo on `unit` into `out` and prints what it found.
pub fn run(unit: &Unit, out: &Path, progress: Progress) -> Result<()> {
    let d = dtg_vib::unit_demo::run(unit, out, &|step| progress.say(step))?;
    drop(progress);
    let hidden: Vec<String> = d
        .hidden
        .iter()
        .map(|h| format!("{}={} ({} {})", h.channel, h.effect, h.value, h.unit))
        .collect();
    println!(
        "The demo's loop on the unit '{}' ({}), a simulated vibration test ({}):",
        unit.name(),
        unit.file(),
        d.record.display()
    );
    println!("hidden from the calibration: {}", hidden.join(", "));
    println!(
        "the loop ({} round(s){}) added:",
        d.rounds,
        if d.converged {
            ", until nothing new was suggested"
        } else {
            ", stopped at the round limit"
        }
    );
    for f in &d.found {
        println!("  {}", found_text(f));
    }
    if d.found.is_empty() {
        println!("  nothing");
    }
    for m in &d.missed {
        println!(
            "  missed: {}={} (hidden {} {})",
            m.channel, m.effect, m.value, m.unit
        );
    }
    println!("channel  val rms baseline  val rms final  (deg/h)  change");
    for (c, b, a) in &d.channel_rms {
        println!(
            "{c:>7}  {b:>16.4}  {a:>13.4}  {:>15}",
            format!("{:+.1}%", 100.0 * (a / b - 1.0))
        );
    }
    let m = dtg_vib::unit_sensor::UnitModel::load(out.join("final").join("model.json"))?;
    super::report::print_parity(&m, &d.parity);
    println!();
    println!("reports (start with {}):", d.index.display());
    println!("  baseline:            {}", d.baseline_report.display());
    println!("  diagnosis:           {}", d.diagnosis_report.display());
    println!("  after the loop:      {}", d.final_report.display());
    println!(
        "  what is left:        {}",
        d.final_diagnosis_report.display()
    );
    Ok(())
}
