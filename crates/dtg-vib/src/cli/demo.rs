//! `dtg-vib demo`: the main job on a built-in default, end to end.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use std::path::PathBuf;

use super::residues::print_residues;

/// The flags of `demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// Output directory.
    #[arg(long, default_value = "demo-out")]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. On another unit the demo
    /// hides effects that suit it (tetra: g2=g_y and g3=col:temp; triad:
    /// gx=g_y in a test along z; dual-triad: gx2=g_x) and runs the loop.
    #[arg(long)]
    unit: Option<String>,
}

/// Runs the demo into its directory and prints what it found.
pub fn run(a: DemoArgs, progress: Progress) -> Result<()> {
    let DemoArgs { out, unit } = a;
    let chosen = super::unit::chosen(unit.as_deref())?;
    outfile::guard_dir("--out", &out, &[], &[])?;
    if let Some(u) = chosen {
        return super::unit::demo::run(&u, &out, progress);
    }
    let summary = dtg_vib::demo::run(&out, &|step| progress.say(step.to_string()))?;
    drop(progress);
    print_demo(&summary);
    Ok(())
}

fn print_demo(s: &dtg_vib::demo::DemoSummary) {
    println!(
        "The paper's procedure on the simulated Z-axis random vibration test ({}):",
        s.record.display()
    );
    print_residues(&s.baseline_residues);
    println!();
    println!(
        "Diagnosis (hidden in the simulation: {}):",
        s.hidden.join(", ")
    );
    for c in &s.diagnosis.channels {
        // Each suggestion with its coefficient and 95% interval.
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
    let added: Vec<String> = s
        .suggested
        .iter()
        .map(|a| format!("{}={}", a.channel, a.effect))
        .collect();
    println!();
    println!(
        "Refitted with {}:",
        if added.is_empty() {
            "nothing to add".into()
        } else {
            added.join(", ")
        }
    );
    println!("channel  val rms before  val rms after  (deg/h)");
    for (ch, b, a) in &s.channel_rms {
        println!(
            "{:>7}  {:>14.4}  {:>13.4}  {:+.1}%",
            ch.name(),
            b,
            a,
            100.0 * (a / b - 1.0)
        );
    }
    print_residues(&s.final_residues);
    println!();
    println!("reports (start with {}):", s.index.display());
    println!("  paper's procedure: {}", s.baseline_report.display());
    println!("  diagnosis:         {}", s.diagnosis_report.display());
    println!("  after the refit:   {}", s.final_report.display());
}
