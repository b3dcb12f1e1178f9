//! `dtg-vib compensate`: the record with a model's prediction removed,
//! written in the unit's column names and units; a causal model runs
//! sample by sample through the onboard evaluator.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::commands::compensate::{Compensated, compensate};
use dtg_vib::unit_sensor::RateReference;
use std::path::PathBuf;

use dtg_vib::commands::records::{open_model, records_of};

/// The flags of `compensate`.
#[derive(Args)]
pub struct CompensateArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Output CSV (the record's columns; each segment's rows from its first
    /// full window on).
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); not needed (a model stores its unit), and
    /// refused when it is not the model's.
    #[arg(long)]
    unit: Option<String>,
}

/// Writes the compensated record and says what was removed.
pub fn run(a: CompensateArgs, progress: Progress) -> Result<()> {
    let CompensateArgs {
        model,
        data,
        out,
        unit,
    } = a;
    let m = open_model(&model, unit.as_deref())?;
    outfile::guard_file(
        "--out",
        &out,
        &[("--model", Some(&model)), ("--data", Some(&data))],
    )?;
    let read = records_of(&m, std::slice::from_ref(&data))?;
    progress.say("compensating");
    let Compensated {
        text,
        rows,
        first_sample,
    } = compensate(&m, &read)?;
    outfile::write_bytes(&out, text).map_err(|e| anyhow::anyhow!("{}: {e}", out.display()))?;
    drop(progress);
    read.say_notes();
    eprintln!(
        "{}",
        rate_reference_note(&m.inner().sensor().rate_reference)
    );
    eprintln!(
        "wrote {} ({rows} rows in the unit's names and units, from {} segment(s): each segment's first {} samples have no full window)",
        out.display(),
        read.records.len(),
        first_sample
    );
    Ok(())
}

/// What `compensate` removes as the rate reference, and how to change it.
fn rate_reference_note(r: &RateReference) -> String {
    let what = match r {
        RateReference::None => "no rate reference (the model was fitted without one)".to_string(),
        RateReference::Earth { site } => format!(
            "the Earth rate at latitude {}° (cluster x north, z up)",
            site.latitude_deg
        ),
        RateReference::Table { rate_deg_s } => format!(
            "a table rate of {}, {}, {} deg/s about cluster x, y, z",
            rate_deg_s[0], rate_deg_s[1], rate_deg_s[2]
        ),
        RateReference::Parity => {
            "the unit's own least-squares rate, sample by sample (the model was fitted in parity on a moving record)".to_string()
        }
    };
    format!(
        "rate reference removed: {what}, as stored in the model; to change it, refit with --earth-rate LAT or --table-rate WX,WY,WZ"
    )
}
