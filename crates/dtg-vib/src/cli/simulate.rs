//! `dtg-vib simulate`: a sensor-unit vibration test from a scenario, written
//! as the record and its ground truth.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::commands;
use std::path::PathBuf;

/// The flags of `simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// Scenario file (TOML, see docs/formats.md).
    #[arg(long, conflicts_with = "builtin")]
    scenario: Option<PathBuf>,
    /// A built-in scenario (each is scenarios/NAME.toml): paper_z_random,
    /// triaxial_clean, triaxial_hidden, demo; the campaign x-axis, y-axis,
    /// z-axis, sine-sweep, flight.
    #[arg(long)]
    builtin: Option<String>,
    /// Override the scenario's seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Override the scenario's duration, s (a shorter run of a long
    /// profile: the schedule and motion are cut, not compressed).
    #[arg(long)]
    duration: Option<f64>,
    /// Output directory (record.csv, calibration.json, truth.json, components.csv, scenario.toml;
    /// with --unit: record.csv in the unit's names and units, calibration.json, truth.json,
    /// scenario.toml, unit.toml).
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. The scenario's [unit] table
    /// names its channels' coefficients and hidden effects.
    #[arg(long)]
    unit: Option<String>,
}

/// Simulates the scenario the flags name and writes its files.
pub fn run(a: SimulateArgs, progress: Progress) -> Result<()> {
    let SimulateArgs {
        scenario,
        builtin,
        seed,
        duration,
        out,
        unit,
    } = a;
    let unit = commands::records::unit_of(unit.as_deref())?;
    let s = commands::simulate::scenario(scenario.as_deref(), builtin.as_deref(), seed, duration)?;
    let files = commands::simulate::files(&unit);
    outfile::guard_dir(
        "--out",
        &out,
        &files,
        &[("--scenario", scenario.as_deref())],
    )?;
    progress.say(format!(
        "simulating '{}' ({} s) on the unit '{}'",
        s.name,
        s.duration_s,
        unit.name()
    ));
    let notes = commands::simulate::simulate_into(&s, &unit, &out)?;
    drop(progress);
    for name in files {
        println!("wrote {}", out.join(name).display());
    }
    for n in &notes {
        eprintln!("note: {n}");
    }
    Ok(())
}
