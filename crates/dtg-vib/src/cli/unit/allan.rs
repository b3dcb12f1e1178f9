//! `allan --unit`: the overlapping Allan deviation and IEEE Std 952 noise
//! terms of every gyro and parity residue of a unit's log, on its longest
//! segment between time gaps (an average never spans a gap), before and,
//! with a model of the unit, after its compensation; `--report` draws them.

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::allan::{SeriesAllan, term_text};
use dtg_vib::unit_sensor::{UnitModel, unit_allan};
use nav_sensors::noise::{NoiseTerm, NoiseTerms};
use nav_sensors::unit::Unit;
use std::path::Path;

/// One series' curve and terms in `allan --unit --json`.
#[derive(serde::Serialize)]
struct Series<'a> {
    name: &'a str,
    tau_s: Vec<f64>,
    adev_deg_h: Vec<f64>,
    arw_deg_per_sqrt_h: String,
    bias_instability_deg_per_h: String,
    rrw_deg_per_h_per_sqrt_h: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    adev_after_deg_h: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    arw_after_deg_per_sqrt_h: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bias_instability_after_deg_per_h: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rrw_after_deg_per_h_per_sqrt_h: Option<String>,
}

fn series(s: &SeriesAllan) -> Series<'_> {
    let after = |f: fn(&NoiseTerms) -> &NoiseTerm| s.terms_after.as_ref().map(|t| term_text(f(t)));
    Series {
        name: &s.name,
        tau_s: s.before.tau_s(),
        adev_deg_h: s.before.adev(),
        arw_deg_per_sqrt_h: term_text(&s.terms_before.arw),
        bias_instability_deg_per_h: term_text(&s.terms_before.bias_instability),
        rrw_deg_per_h_per_sqrt_h: term_text(&s.terms_before.rrw),
        adev_after_deg_h: s.after.as_ref().map(|a| a.adev()),
        arw_after_deg_per_sqrt_h: after(|t| &t.arw),
        bias_instability_after_deg_per_h: after(|t| &t.bias_instability),
        rrw_after_deg_per_h_per_sqrt_h: after(|t| &t.rrw),
    }
}

/// What `allan --unit` is given besides the unit and the record.
pub struct AllanRun<'a> {
    /// A model of the unit: adds the curves after its compensation.
    pub model: Option<&'a UnitModel>,
    /// Two-sided confidence level of the intervals.
    pub confidence: f64,
    /// One JSON object on stdout.
    pub json: bool,
    /// Where to draw the figures and index.html.
    pub report: Option<&'a Path>,
}

/// Computes and prints (or writes as JSON) every channel's and residue's terms.
pub fn allan(unit: &Unit, data: &Path, run: AllanRun<'_>, progress: Progress) -> Result<()> {
    let min = run
        .model
        .map_or(2, |m| 2 * m.inner().preprocess().window.length());
    let read = super::read_records(&[data.to_path_buf()], unit, min)?;
    let (name, r) = read
        .records
        .iter()
        .max_by_key(|(_, r)| r.len())
        .expect("read_records gives at least one segment");
    progress.say("computing Allan deviations");
    let a = unit_allan(unit, run.model, r, run.confidence)?;
    let page = match run.report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(dtg_vib::report::write_allan_report(&a, name, dir)?)
        }
        None => None,
    };
    drop(progress);
    read.say_notes();
    let channels: Vec<Series<'_>> = a.channels.iter().map(series).collect();
    let residues: Vec<Series<'_>> = a.residues.iter().map(series).collect();
    if run.json {
        let v = serde_json::json!({
            "unit": unit.name(),
            "segment": name,
            "samples": a.samples,
            "first_sample": a.first_sample,
            "tau0_s": a.tau0_s,
            "confidence": run.confidence,
            "compensated": a.compensated,
            "channels": channels,
            "residues": residues,
        });
        println!("{v}");
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    println!(
        "{name}: {} samples{}, τ₀ {:.4} s (the longest segment between gaps); intervals at {}",
        a.samples,
        match a.first_sample {
            0 => String::new(),
            f => format!(
                " from sample {f} (the model's first full window: before and after cover the same samples)"
            ),
        },
        a.tau0_s,
        run.confidence
    );
    println!("series  ARW deg/√h  |  bias instability deg/h  |  RRW deg/h/√h");
    for s in channels.iter().chain(&residues) {
        println!(
            "{:>6}  {}  |  {}  |  {}",
            s.name, s.arw_deg_per_sqrt_h, s.bias_instability_deg_per_h, s.rrw_deg_per_h_per_sqrt_h
        );
        if let (Some(arw), Some(bi), Some(rrw)) = (
            &s.arw_after_deg_per_sqrt_h,
            &s.bias_instability_after_deg_per_h,
            &s.rrw_after_deg_per_h_per_sqrt_h,
        ) {
            println!("{:>6}  {arw}  |  {bi}  |  {rrw}", "after");
        }
    }
    if let Some(note) = super::no_residue_note(unit) {
        println!("{note}");
    }
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}
