//! `dtg-vib compensate`: the record with a model's prediction removed.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::apply::Applied;
use dtg_vib::model::CompensationModel;
use nav_sensors::record::Record;
use std::path::PathBuf;

/// The flags of `compensate`.
#[derive(Args)]
pub struct CompensateArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Output CSV (same columns; rows from the first full window on).
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
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
    if let Some(m) = super::unit::model_unit(&model, unit.as_deref())? {
        outfile::guard_file(
            "--out",
            &out,
            &[("--model", Some(&model)), ("--data", Some(&data))],
        )?;
        return super::unit::apply::compensate(&m, &data, &out, progress);
    }
    outfile::guard_file(
        "--out",
        &out,
        &[("--model", Some(&model)), ("--data", Some(&data))],
    )?;
    let model = CompensationModel::load(&model)?;
    let record = Record::read_csv(&data)?;
    progress.say("compensating");
    let applied = Applied::unsplit(&model, &record)?;
    progress.clear();
    eprintln!(
        "{}",
        rate_reference_note(&model.preprocess().rate_reference)
    );
    applied.compensated_record().write_csv(&out)?;
    drop(progress);
    eprintln!(
        "wrote {} ({} rows: the first {} samples have no full window)",
        out.display(),
        record.len() - applied.prepared.first_sample(),
        applied.prepared.first_sample()
    );
    Ok(())
}

/// What `compensate` removes as the rate reference, and how to change it.
fn rate_reference_note(r: &dtg_vib::pipeline::RateReference) -> String {
    use dtg_vib::pipeline::RateReference;
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
    };
    format!(
        "rate reference removed: {what}, as stored in the model; to change it, refit with --earth-rate LAT or --table-rate WX,WY,WZ"
    )
}
