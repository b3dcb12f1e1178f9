//! `dtg-vib demo`: the main job on a built-in default, end to end, on any
//! unit ([`dtg_vib::demo`]), and what it prints: what was hidden, the
//! baseline's residues, the diagnosis, what the refit found against the
//! truth, each channel's rms before and after, the residues with fault
//! detection, and where the pages are.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::demo::{Demo, DemoOptions, found_text, hidden_text};
use std::path::PathBuf;

use super::report::print_parity;
use super::residues::print_residues;
use dtg_vib::commands::records::unit_of;

/// The flags of `demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// Output directory.
    #[arg(long, default_value = "demo-out")]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. The demo hides effects
    /// that suit it (paper: Y1's temperature sensitivity in the Z-axis
    /// test; tetra: g2=g_y and g3=col:temp; triad: gx=g_y in a test along z;
    /// dual-triad: gx2=g_x; any other unit: g_y on its first rate gyro or
    /// g_S on its first DTG axis) and runs the loop.
    #[arg(long)]
    unit: Option<String>,
    /// Windowed signals, comma-separated (the unit's accelerometers or
    /// extra columns), or `auto` (chosen from the record, as `fit`);
    /// default the unit's accelerometer along z (the paper's az).
    #[arg(long = "window-signals", value_delimiter = ',')]
    window_signals: Option<Vec<String>>,
}

/// Runs the demo into its directory and prints what it found.
pub fn run(a: DemoArgs, progress: Progress) -> Result<()> {
    let DemoArgs {
        out,
        unit,
        window_signals,
    } = a;
    let unit = unit_of(unit.as_deref())?;
    if let Some(w) = &window_signals
        && w.len() > 1
        && w.iter().any(|s| s.trim() == "auto")
    {
        anyhow::bail!(
            "--window-signals {}: auto chooses the signals itself; give auto alone or a list of signals",
            w.join(",")
        );
    }
    outfile::guard_dir("--out", &out, &[], &[])?;
    let options = DemoOptions { window_signals };
    let d = dtg_vib::demo::run(&unit, &options, &out, &|step| progress.say(step))?;
    drop(progress);
    println!(
        "The demo on the unit '{}' ({}), a simulated vibration test ({}):",
        unit.name(),
        unit.file(),
        d.record.display()
    );
    println!(
        "hidden from the calibration: {}",
        hidden_text(&d.hidden).join(", ")
    );
    if !d.baseline_residues.is_empty() {
        println!("The baseline (bias and the network, no effect):");
        print_residues(&d.baseline_residues);
    }
    println!();
    print_diagnosis(&d);
    println!();
    print_refit(&d);
    if !d.final_residues.is_empty() {
        print_residues(&d.final_residues);
    }
    let m = dtg_vib::unit_sensor::UnitModel::load(out.join("final").join("model.json"))?;
    print_parity(&m, &d.parity);
    println!();
    println!("reports (start with {}):", d.index.display());
    println!("  baseline:            {}", d.baseline_report.display());
    println!("  diagnosis:           {}", d.diagnosis_report.display());
    println!("  after the refit:     {}", d.final_report.display());
    println!(
        "  what is left:        {}",
        d.final_diagnosis_report.display()
    );
    Ok(())
}

/// The baseline's diagnosis: each channel's rms and what it suggests, with
/// its coefficient and 95% interval.
fn print_diagnosis(d: &Demo) {
    println!("Diagnosis of the baseline:");
    for c in &d.diagnosis.channels {
        let suggested: Vec<String> = c
            .suggested
            .iter()
            .map(|id| match c.candidates.iter().find(|k| &k.effect == id) {
                Some(k) => format!(
                    "{id} ({:.3} ± {:.3} {}, 95% CI {:.3} to {:.3})",
                    k.coef, k.coef_se, k.unit, k.coef_ci95[0], k.coef_ci95[1]
                ),
                None => id.clone(),
            })
            .collect();
        println!(
            "  {:>3}: validation rms {:.4} deg/h; suggested: {}",
            c.channel,
            c.rms,
            if suggested.is_empty() {
                "nothing".into()
            } else {
                suggested.join(", ")
            }
        );
    }
}

/// What the refit added and found against the truth, and each channel's
/// validation rms before and after.
fn print_refit(d: &Demo) {
    let added: Vec<String> = d.added.iter().map(|(c, e)| format!("{c}={e}")).collect();
    println!(
        "Refitted with {} ({} fit(s){}):",
        if added.is_empty() {
            "nothing to add".into()
        } else {
            added.join(", ")
        },
        d.rounds,
        if d.converged {
            ", until nothing new was suggested"
        } else {
            "; the refit's diagnosis still suggests more: run dtg-vib explain on the record"
        }
    );
    for f in &d.found {
        println!("  {}", found_text(f));
    }
    for m in &d.missed {
        println!(
            "  missed: {}={} (hidden {} {})",
            m.channel, m.effect, m.value, m.unit
        );
    }
    println!("channel  val rms before  val rms after  (deg/h)  change");
    for (c, b, a) in &d.channel_rms {
        println!(
            "{c:>7}  {b:>14.4}  {a:>13.4}  {:>15}",
            format!("{:+.1}%", 100.0 * (a / b - 1.0))
        );
    }
}
