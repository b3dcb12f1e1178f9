//! `dtg-vib simulate`: a sensor-unit vibration test from a scenario, written
//! as the record and its ground truth.

use anyhow::{Context, Result};
use clap::Args;
use cli_support::progress::Progress;
use nav_sensors::sim::Scenario;
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
    let unit = super::records::unit_of(unit.as_deref())?;
    let scenario_path = scenario.clone();
    let mut s = match (scenario, builtin) {
        (Some(path), _) => Scenario::load(&path)?,
        (None, Some(name)) => Scenario::builtin(&name).with_context(|| {
            format!(
                "unknown built-in scenario '{name}' (valid: {})",
                Scenario::BUILTIN.join(", ")
            )
        })?,
        (None, None) => Scenario::default(),
    };
    if let Some(seed) = seed {
        s.seed = seed;
    }
    if let Some(d) = duration {
        s.duration_s = d;
    }
    if let Some(p) = &scenario_path {
        // Named with the file, before anything is written.
        s.validate()
            .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?;
    }
    simulate_unit(&unit, &s, &out, scenario_path.as_deref(), progress)
}

/// The scenario's physics on the unit's gyros and accelerometers, written
/// in the unit's file formats ([`nav_sensors::unit::FileFormat`]).
fn simulate_unit(
    unit: &nav_sensors::unit::Unit,
    s: &Scenario,
    out: &std::path::Path,
    scenario_path: Option<&std::path::Path>,
    progress: Progress,
) -> Result<()> {
    use nav_sensors::sim::UnitSimulation;
    outfile::guard_dir(
        "--out",
        out,
        &UnitSimulation::files(unit),
        &[("--scenario", scenario_path)],
    )?;
    progress.say(format!(
        "simulating '{}' ({} s) on the unit '{}'",
        s.name,
        s.duration_s,
        unit.name()
    ));
    let sim = nav_sensors::sim::simulate_unit(unit, s)?;
    sim.write_dir(out).with_context(|| {
        format!(
            "scenario '{}' gives values no reader takes: check the magnitudes and units of its numbers",
            s.name
        )
    })?;
    drop(progress);
    for name in UnitSimulation::files(unit) {
        println!("wrote {}", out.join(name).display());
    }
    for n in &sim.truth.not_applied {
        eprintln!("note: {n}");
    }
    Ok(())
}
