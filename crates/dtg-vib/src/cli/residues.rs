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
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
    #[arg(long)]
    unit: Option<String>,
    /// Print one JSON object on stdout (units other than the paper's):
    /// the residues' rms and what fault detection found.
    #[arg(long)]
    json: bool,
    /// Fault detection (units of four gyros or more): the gyros' white
    /// noise per sample, deg/h; default read from the record.
    #[arg(long = "fdi-sigma", value_parser = super::parse::parse_sigma)]
    fdi_sigma: Option<f64>,
    /// Fault detection: the false-alarm probability per sample.
    #[arg(long = "fdi-false-alarm", default_value_t = dtg_vib::unit_sensor::fdi::DEFAULT_FALSE_ALARM, value_parser = super::parse::parse_alpha)]
    fdi_false_alarm: f64,
}

/// The flags only a unit other than the paper's takes, refused on the
/// paper's path (whose output is a contract): which, and what to do.
fn unit_only(a: &ResiduesArgs) -> Result<()> {
    let given = [
        ("--json", a.json),
        ("--fdi-sigma", a.fdi_sigma.is_some()),
        (
            "--fdi-false-alarm",
            a.fdi_false_alarm != dtg_vib::unit_sensor::fdi::DEFAULT_FALSE_ALARM,
        ),
    ];
    if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
        anyhow::bail!(
            "{flag}: residues takes it on the unit path only (--unit tetra, dual-triad or a unit file, or a model of one), so that the paper's residues output stays as it was; for the paper's geometry give --unit a copy of units/paper.toml with temperature = \"temp\" under [columns]"
        );
    }
    Ok(())
}

/// Writes the residues and, with a model, prints their rms before and after.
pub fn run(a: ResiduesArgs, progress: Progress) -> Result<()> {
    let fdi = super::unit::residues::FdiOptions {
        sigma: a.fdi_sigma,
        false_alarm: a.fdi_false_alarm,
    };
    let json = a.json;
    let paper_only = unit_only(&a);
    let ResiduesArgs {
        data,
        model,
        out,
        unit,
        ..
    } = a;
    let unit_model = match &model {
        Some(m) => super::unit::model_unit(m, unit.as_deref())?,
        None => None,
    };
    let chosen = match &unit_model {
        Some(m) => Some(m.unit().clone()),
        None if model.is_none() => super::unit::chosen(unit.as_deref())?,
        None => None,
    };
    if let Some(u) = chosen {
        outfile::guard_file(
            "--out",
            &out,
            &[("--data", Some(&data)), ("--model", model.as_deref())],
        )?;
        return super::unit::residues::residues(
            &u,
            unit_model.as_ref(),
            &data,
            &out,
            fdi,
            json,
            progress,
        );
    }
    paper_only?;
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

/// The residue table on the rows `rows` names: each residue's rms before and
/// after and how many times better or worse, then the six pooled (the rms of
/// all six residues together, the one figure a campaign compares models by).
pub fn print_residues_on(stats: &[dtg_vib::parity::ResidueStats], rows: &str) {
    println!(
        "residue  rms before  rms after  {:<24}  change",
        format!("(deg/h, {rows})")
    );
    let row = |name: &str, before: f64, after: f64| {
        println!(
            "{name:>7}  {before:>10.4}  {after:>9.4}  {:24}  {}",
            "",
            change(before, after)
        );
    };
    for s in stats {
        row(s.residue.name(), s.rms_before, s.rms_after);
    }
    let pooled = |rms: fn(&dtg_vib::parity::ResidueStats) -> f64| {
        (stats.iter().map(|s| rms(s).powi(2)).sum::<f64>() / stats.len().max(1) as f64).sqrt()
    };
    row("pooled", pooled(|s| s.rms_before), pooled(|s| s.rms_after));
}

/// How many times smaller (better) or larger (worse) the rms is after: a
/// ratio below one, printed as such, read as a reduction where it was a
/// sixfold worsening.
///
/// The ratio has two decimals either way, as the reduction had, in six
/// columns so that the "×" of a table's rows line up.
fn change(before: f64, after: f64) -> String {
    let ratio = before / after;
    if !(ratio.is_finite() && ratio > 0.0) {
        format!("{:>6}", "—")
    } else if ratio >= 1.0 {
        format!("{ratio:>6.2}× better")
    } else {
        format!("{:>6.2}× worse", 1.0 / ratio)
    }
}

#[cfg(test)]
mod tests {
    use super::change;

    #[test]
    fn a_change_says_better_or_worse_with_its_factor() {
        assert_eq!(change(4.07, 1.0), "  4.07× better");
        assert_eq!(change(2.3748, 14.5898), "  6.14× worse");
        assert_eq!(change(1.0, 1.0), "  1.00× better");
        // No ratio to give: a dash, never "inf× better".
        assert_eq!(change(1.0, 0.0), "     —");
        assert_eq!(change(0.0, 0.0), "     —");
    }
}
