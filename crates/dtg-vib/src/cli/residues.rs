//! `dtg-vib residues`: the parity residues K0..K5 of a record (eq. 6), and
//! with a model the compensated ones; the residue tables other commands print.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::apply::{Applied, write_residues};
use dtg_vib::model::CompensationModel;
use nav_sensors::record::Record;
use std::path::PathBuf;

/// The flags of `residues`.
#[derive(Args)]
pub struct ResiduesArgs {
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Model file: adds K*_pre (calibrated, filtered) and K*_comp (compensated) columns.
    #[arg(long)]
    model: Option<PathBuf>,
    /// Output CSV.
    #[arg(long)]
    out: PathBuf,
}

/// Writes the residues and, with a model, prints their rms before and after.
pub fn run(a: ResiduesArgs, progress: Progress) -> Result<()> {
    let ResiduesArgs { data, model, out } = a;
    outfile::guard_file(
        "--out",
        &out,
        &[("--data", Some(&data)), ("--model", model.as_deref())],
    )?;
    let record = Record::read_csv(&data)?;
    let applied = match &model {
        Some(m) => {
            let m = CompensationModel::load(m)?;
            let a = Applied::unsplit(&m, &record)?;
            Some((m, a))
        }
        None => None,
    };
    write_residues(&out, &record, applied.as_ref().map(|(_, a)| a))?;
    drop(progress);
    // The validation rows of the model's split, if this record has them.
    if let Some((m, a)) = &applied
        && let Ok((_, val)) = m.rows(&a.prepared)
    {
        print_residues(&a.residues.stats(&val));
    }
    eprintln!("wrote {}", out.display());
    Ok(())
}

/// The residue table on the validation rows.
pub fn print_residues(stats: &[dtg_vib::parity::ResidueStats]) {
    print_residues_on(stats, "validation rows");
}

/// The residue table on the rows `rows` names.
pub fn print_residues_on(stats: &[dtg_vib::parity::ResidueStats], rows: &str) {
    println!("residue  rms before  rms after  (deg/h, {rows:<15})  reduction");
    for s in stats {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}  {:>35.2}×",
            s.residue.name(),
            s.rms_before,
            s.rms_after,
            s.reduction
        );
    }
}
