//! A simulation as `dtg-vib simulate` writes it: the scenario the flags
//! name (a file, a built-in, the paper's Z-axis random test by default,
//! with the seed and duration given), simulated on the unit and written
//! as its record, calibration and truth files.

use anyhow::{Context, Result};
use nav_sensors::sim::{Scenario, Simulation, UnitSimulation};
use nav_sensors::unit::Unit;
use std::path::Path;

/// The scenario: a file, a built-in by name, or the default; `seed` and
/// `duration_s` override its own.
pub fn scenario(
    file: Option<&Path>,
    builtin: Option<&str>,
    seed: Option<u64>,
    duration_s: Option<f64>,
) -> Result<Scenario> {
    let mut s = match (file, builtin) {
        (Some(path), _) => Scenario::load(path)?,
        (None, Some(name)) => Scenario::builtin(name).with_context(|| {
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
    if let Some(d) = duration_s {
        s.duration_s = d;
    }
    if let Some(p) = file {
        // Named with the file, before anything is written.
        s.validate()
            .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?;
    }
    Ok(s)
}

/// The files a simulation writes into its directory, on `unit` (None: the
/// paper's own format).
pub fn files(unit: Option<&Unit>) -> &'static [&'static str] {
    match unit {
        Some(_) => &UnitSimulation::FILES,
        None => &Simulation::FILES,
    }
}

/// Simulates `s` on `unit` (None: the paper's unit in its own format) and
/// writes its files into `out`, which the caller has guarded; returns the
/// notes on hidden effects the unit could not take.
pub fn simulate_into(s: &Scenario, unit: Option<&Unit>, out: &Path) -> Result<Vec<String>> {
    let unreadable = || {
        format!(
            "scenario '{}' gives values no reader takes: check the magnitudes and units of its numbers",
            s.name
        )
    };
    match unit {
        Some(unit) => {
            let sim = nav_sensors::sim::simulate_unit(unit, s)?;
            sim.write_dir(out).with_context(unreadable)?;
            Ok(sim.truth.not_applied.clone())
        }
        None => {
            let sim = nav_sensors::sim::simulate(s)?;
            sim.write_dir(out).with_context(unreadable)?;
            Ok(Vec::new())
        }
    }
}
