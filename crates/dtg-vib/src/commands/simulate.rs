//! A simulation as `dtg-vib simulate` writes it: the scenario the flags
//! name (a file, a built-in, the paper's Z-axis random test by default,
//! with the seed and duration given), simulated on the unit and written
//! as its record, calibration and truth files.

use anyhow::{Context, Result};
use nav_sensors::sim::{Scenario, UnitSimulation};
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

/// The files a simulation on `unit` writes into its directory, in the
/// unit's file formats ([`nav_sensors::unit::FileFormat`]).
pub fn files(unit: &Unit) -> [&'static str; 5] {
    UnitSimulation::files(unit)
}

/// Simulates `s` on `unit` and writes its files into `out`, which the
/// caller has guarded; returns the notes on hidden effects the unit could
/// not take.
pub fn simulate_into(s: &Scenario, unit: &Unit, out: &Path) -> Result<Vec<String>> {
    let sim = nav_sensors::sim::simulate_unit(unit, s)?;
    sim.write_dir(out).with_context(|| {
        format!(
            "scenario '{}' gives values no reader takes: check the magnitudes and units of its numbers",
            s.name
        )
    })?;
    Ok(sim.truth.not_applied.clone())
}
