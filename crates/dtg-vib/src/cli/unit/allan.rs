//! `allan --unit`: the overlapping Allan deviation and IEEE Std 952 noise
//! terms of every gyro and parity residue of a unit's log, on its longest
//! segment between time gaps (an average never spans a gap).

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::allan::term_text;
use nav_sensors::noise::{AllanCurve, NoiseTerms};
use nav_sensors::unit::Unit;
use std::path::Path;

/// One series' curve and terms.
#[derive(serde::Serialize)]
struct Series {
    name: String,
    tau_s: Vec<f64>,
    adev_deg_h: Vec<f64>,
    arw_deg_per_sqrt_h: String,
    bias_instability_deg_per_h: String,
    rrw_deg_per_h_per_sqrt_h: String,
}

fn series(name: &str, y: &[f64], tau0: f64, confidence: f64) -> Result<Series> {
    let curve = AllanCurve::octaves(y, tau0, confidence)?;
    let terms = NoiseTerms::fit(&curve);
    Ok(Series {
        name: name.to_string(),
        tau_s: curve.points.iter().map(|p| p.tau_s).collect(),
        adev_deg_h: curve.points.iter().map(|p| p.adev).collect(),
        arw_deg_per_sqrt_h: term_text(&terms.arw),
        bias_instability_deg_per_h: term_text(&terms.bias_instability),
        rrw_deg_per_h_per_sqrt_h: term_text(&terms.rrw),
    })
}

/// Computes and prints (or writes as JSON) every channel's and residue's terms.
pub fn allan(
    unit: &Unit,
    data: &Path,
    confidence: f64,
    json: bool,
    progress: Progress,
) -> Result<()> {
    let read = super::read_records(&[data.to_path_buf()], unit, 2)?;
    let (name, r) = read
        .records
        .iter()
        .max_by_key(|(_, r)| r.len())
        .expect("read_records gives at least one segment");
    progress.say("computing Allan deviations");
    let tau0 = r.dt();
    let mut channels = Vec::new();
    for (k, g) in unit.gyro_names().iter().enumerate() {
        channels.push(series(g, r.gyro_at(k), tau0, confidence)?);
    }
    let mut residues = Vec::new();
    for (k, p) in unit.residue_names().iter().enumerate() {
        let y: Vec<f64> = (0..r.len())
            .map(|i| unit.residues(&r.gyro_row(i))[k])
            .collect();
        residues.push(series(p, &y, tau0, confidence)?);
    }
    drop(progress);
    read.say_notes();
    if json {
        let v = serde_json::json!({
            "unit": unit.name(),
            "segment": name,
            "samples": r.len(),
            "tau0_s": tau0,
            "confidence": confidence,
            "channels": channels,
            "residues": residues,
        });
        println!("{v}");
        return Ok(());
    }
    println!(
        "{name}: {} samples, τ₀ {:.4} s (the longest segment between gaps); intervals at {confidence}",
        r.len(),
        tau0
    );
    println!("series  ARW deg/√h  |  bias instability deg/h  |  RRW deg/h/√h");
    for s in channels.iter().chain(&residues) {
        println!(
            "{:>6}  {}  |  {}  |  {}",
            s.name, s.arw_deg_per_sqrt_h, s.bias_instability_deg_per_h, s.rrw_deg_per_h_per_sqrt_h
        );
    }
    if let Some(note) = super::no_residue_note(unit) {
        println!("{note}");
    }
    Ok(())
}
