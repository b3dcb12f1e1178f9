//! `report` with a model of a unit other than the paper's: the unit's page
//! ([`dtg_vib::unit_page`]) — per channel measured against predicted, rms
//! before and after, the effects with their intervals, the parity residues
//! with fault detection, the Allan figure.

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::unit_page::{Page, Parity, write_page};
use dtg_vib::unit_sensor::UnitModel;
use dtg_vib::unit_sensor::fdi;
use std::path::Path;

/// Prints the residues' rms and the fault-detection lines (or, for three
/// gyros, that there is no residue).
pub fn print_parity(m: &UnitModel, p: &Parity) {
    if p.residues.is_empty() {
        if let Some(note) = super::no_residue_note(m.unit()) {
            println!("{note}");
        }
        return;
    }
    println!("residue  rms before  rms after  (deg/h, every sample)");
    for r in &p.residues {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}",
            r.name,
            r.before,
            r.after.unwrap_or(f64::NAN)
        );
    }
    if let Some(f) = &p.fdi {
        for (what, s) in &f.found {
            println!("{}", fdi::line(what, s, &f.setting));
        }
    }
}

/// `report` of a unit's model (the model stores its unit).
pub fn report(
    m: &UnitModel,
    model: &Path,
    data: &Path,
    baseline: Option<&Path>,
    out: &Path,
    progress: Progress,
) -> Result<()> {
    let base = baseline.map(UnitModel::load).transpose()?;
    if let (Some(b), Some(path)) = (&base, baseline)
        && b.unit() != m.unit()
    {
        anyhow::bail!(
            "--baseline {}: fitted with the unit '{}', the model with '{}': a baseline must be a model of the same unit",
            path.display(),
            b.unit().name(),
            m.unit().name()
        );
    }
    let read = super::apply::records_of(m, &[data.to_path_buf()])?;
    progress.say("applying the model and drawing figures");
    let data = [data.to_path_buf()];
    let written = write_page(
        m,
        &read.records,
        Page {
            baseline: base.as_ref().zip(baseline),
            ..Page::new(model, &data)
        },
        out,
    )?;
    let (index, parity) = (written.index, written.parity);
    drop(progress);
    read.say_notes();
    print_parity(m, &parity);
    println!("report: {}", index.display());
    Ok(())
}
