//! The demo's loop on any unit: simulate a test with effects hidden from
//! the unit's ground calibration, fit, run the explain loop (diagnose, add
//! what it names, refit), and write the pages — the baseline's, the
//! diagnoses', and the final one linking them, again as `out/index.html`.
//!
//! The hidden effects suit the unit (issue 22 §6): `tetra` a g-sensitivity
//! along y on g2 and a temperature sensitivity on g3 in the tri-axial test;
//! `triad` a g-sensitivity along y on gx in a vibration test along z with
//! the fixture's cross-axis motion on y (a g² along z would be a function
//! of the az windows the network sees, and test nothing); `dual-triad` a
//! g-sensitivity along x on gx2. Any other unit gets a g-sensitivity along
//! y on its first rate gyro (or g_S on its first DTG axis), in the
//! tri-axial test, or the z test for three gyros. Each case's record
//! length and seed are those `tests/unit_loop.rs` accepts.

use crate::error::DtgVibError;
use crate::pipeline::RateReference;
use crate::report::{DiagnosisExtra, Wording, write_diagnosis_report_of};
use crate::unit_page::{Page, Parity, write_page};
use crate::unit_sensor::{UnitEffect, UnitModel, UnitSensor, to_signals};
use nav_sensors::geometry::Axis;
use nav_sensors::sim::{Scenario, UnitHiddenEffect, simulate_unit};
use nav_sensors::unit::{GyroModel, Unit};
use nav_sensors::vibration::Drive;
use std::path::{Path, PathBuf};
use sysid::inference::Coefficient;

/// One effect hidden in the simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Hidden {
    /// The gyro.
    pub channel: String,
    /// The scenario's term id (`g_y`, `temp`).
    pub term: String,
    /// The id the loop names it by (`g_y`, `col:temp`).
    pub effect: String,
    /// The true coefficient.
    pub value: f64,
    /// Its unit.
    pub unit: &'static str,
}

/// What the demo hides on `unit`, and in which test: the scenario.
pub fn scenario(unit: &Unit) -> Result<(Scenario, Vec<Hidden>), DtgVibError> {
    let is = |name: &str| Unit::builtin(name).is_ok_and(|b| &b == unit);
    let rate = |channel: &str, term: &str, value: f64| Hidden {
        channel: channel.into(),
        term: term.into(),
        effect: if term == "temp" {
            "col:temp".into()
        } else {
            term.into()
        },
        value,
        unit: if term == "temp" {
            "deg/h/°C"
        } else {
            "deg/h/g"
        },
    };
    let (hidden, along_z, seed) = if is("tetra") {
        (
            vec![rate("g2", "g_y", 0.5), rate("g3", "temp", 0.05)],
            false,
            31,
        )
    } else if is("triad") {
        (vec![rate("gx", "g_y", 2.0)], true, 32)
    } else if is("dual-triad") {
        (vec![rate("gx2", "g_x", 0.5)], false, 33)
    } else {
        let g = &unit.gyros()[0];
        let h = match g.model {
            GyroModel::Rate => rate(&g.name, "g_y", 0.5),
            GyroModel::Dtg { .. } => Hidden {
                channel: g.name.clone(),
                term: "g_S".into(),
                effect: "g_S".into(),
                value: 0.5,
                unit: "deg/h/g",
            },
        };
        (vec![h], unit.gyros().len() == 3, 31)
    };
    let mut s = Scenario::triaxial_hidden();
    s.name = "unit_demo".into();
    s.hidden.clear();
    s.duration_s = 60.0;
    s.seed = seed;
    for h in &hidden {
        let is_dtg = matches!(
            unit.gyros()
                .iter()
                .find(|g| g.name == h.channel)
                .map(|g| &g.model),
            Some(GyroModel::Dtg { .. })
        );
        if is_dtg {
            // The demo's own ids (g_S): they parse.
            let t = h.term.parse().expect("the demo's DTG term id parses");
            s.unit
                .dtg
                .entry(h.channel.clone())
                .or_default()
                .set(t, h.value);
        } else {
            let t: nav_sensors::rate::RateTerm =
                h.term.parse().expect("the demo's rate term ids parse");
            s.unit
                .rate
                .entry(h.channel.clone())
                .or_default()
                .set(t, h.value);
        }
        s.unit.hidden.push(UnitHiddenEffect {
            channel: h.channel.clone(),
            term: h.term.clone(),
        });
    }
    if along_z {
        shake_along_z(&mut s);
    }
    Ok((s, hidden))
}

/// The tri-axial test made a test along z: no drive on x, the drive on y
/// 10 dB down (the fixture's cross-axis motion, independent of z's), so
/// that a g-sensitivity to y is not a function of the az windows.
///
/// ```
/// let mut s = nav_sensors::sim::Scenario::triaxial_hidden();
/// dtg_vib::unit_demo::shake_along_z(&mut s);
/// assert!(s.vibration.drives.iter().all(|d| d.axis() != nav_sensors::geometry::Axis::X));
/// ```
pub fn shake_along_z(s: &mut Scenario) {
    s.vibration.drives.retain(|d| d.axis() != Axis::X);
    for d in &mut s.vibration.drives {
        if let Drive::Random {
            axis: Axis::Y,
            gain_db,
            ..
        } = d
        {
            *gain_db = -10.0;
        }
    }
}

/// An effect of the final model, against the truth if it was hidden.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    /// The gyro.
    pub channel: String,
    /// The effect id.
    pub effect: String,
    /// Its coefficient, standard error and 95% interval.
    pub coefficient: Option<Coefficient>,
    /// The hidden value, if this effect was hidden.
    pub truth: Option<f64>,
}

impl Found {
    /// Whether its 95% interval covers the hidden value.
    pub fn covers(&self) -> Option<bool> {
        let (c, t) = (self.coefficient.as_ref()?, self.truth?);
        Some(c.ci95[0] <= t && t <= c.ci95[1])
    }
}

/// What the demo found and where it wrote it.
#[derive(Debug, Clone)]
pub struct UnitDemo {
    /// The simulated record.
    pub record: PathBuf,
    /// What was hidden.
    pub hidden: Vec<Hidden>,
    /// Every effect of the final model.
    pub found: Vec<Found>,
    /// Hidden effects the loop did not add.
    pub missed: Vec<Hidden>,
    /// Per channel: validation rms of the baseline and of the final model, deg/h.
    pub channel_rms: Vec<(String, f64, f64)>,
    /// The residues and fault detection of the final model.
    pub parity: Parity,
    /// Rounds the loop made, and whether it converged.
    pub rounds: usize,
    /// Whether the loop stopped because nothing new was suggested.
    pub converged: bool,
    /// The baseline's page.
    pub baseline_report: PathBuf,
    /// The baseline's diagnosis page.
    pub diagnosis_report: PathBuf,
    /// The final model's diagnosis page.
    pub final_diagnosis_report: PathBuf,
    /// The final page.
    pub final_report: PathBuf,
    /// `out/index.html`: the final page again, the one to open first.
    pub index: PathBuf,
}

fn mkdir(p: &Path) -> Result<(), DtgVibError> {
    std::fs::create_dir_all(p).map_err(|source| DtgVibError::Output {
        path: p.to_path_buf(),
        source,
    })
}

/// Runs the demo on `unit` into `out`, saying each step to `progress`.
pub fn run(
    unit: &Unit,
    out: &Path,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<UnitDemo, DtgVibError> {
    mkdir(out)?;
    progress("simulating the vibration test");
    let (s, hidden) = scenario(unit)?;
    let sim = simulate_unit(unit, &s)?;
    let sim_dir = out.join("simulation");
    sim.write_dir(&sim_dir)?;
    let record = sim_dir.join("record.csv");
    let sensor = UnitSensor {
        unit: unit.clone(),
        calibration: Some(sim.calibration.clone()),
        rate_reference: RateReference::None,
    };
    let signals = to_signals(&sim.record)?;
    let name = record.display().to_string();
    let named = [(name.clone(), &signals)];
    let records = [(name, sim.record.clone())];
    let mut options = sysid::FitOptions::<UnitEffect>::new(unit.gyros().len());
    // The demo's window, az alone, until `demo` takes --window-signals.
    options.recipe.preprocess.window =
        sysid::WindowSpec::new(vec!["az".into()], 50).map_err(sysid::SysidError::from)?;

    progress("fitting the baseline model");
    let (base, _) = sysid::fit_records(&sensor, &named, &options, &|_| {})?;
    let base = UnitModel::of(base);
    let base_path = out.join("baseline").join("model.json");
    mkdir(&out.join("baseline"))?;
    base.save(&base_path)?;
    let data = [record.clone()];
    progress("writing the baseline report");
    let baseline_report = write_page(
        &base,
        &records,
        Page {
            lead: vec![
                "The baseline: bias and the network over the accelerometers' windows, no physical effect (the demo's first fit)."
                    .into(),
            ],
            ..Page::new(&base_path, &data)
        },
        &out.join("baseline").join("report"),
    )?
    .index;

    progress("running the loop: diagnose, add what it names, refit");
    let diagnose = sysid::diagnose::DiagnoseOptions::default();
    let e = sysid::explain::explain(&sensor, &named, &options, &diagnose, 5, &|_| {})?;
    let wording = Wording::of_unit(unit);
    let min_err = diagnose.rank.min_err();
    let first = &e.rounds.first().expect("at least one round").diagnosis;
    let diagnosis_report =
        write_diagnosis_report_of(first, min_err, &wording, &out.join("diagnosis"))?;
    let last = &e.rounds.last().expect("at least one round").diagnosis;
    let final_diagnosis_report = write_diagnosis_report_of(
        last,
        min_err,
        &wording,
        &out.join("final").join("diagnosis"),
    )?;
    let model = UnitModel::of(e.model);
    let model_path = out.join("final").join("model.json");
    model.save(&model_path)?;

    let truth = |channel: &str, effect: &str| {
        hidden
            .iter()
            .find(|h| h.channel == channel && h.effect == effect)
            .map(|h| h.value)
    };
    let found: Vec<Found> = model
        .inner()
        .channels()
        .iter()
        .flat_map(|c| {
            c.effects().iter().enumerate().map(move |(j, eff)| Found {
                channel: c.channel(),
                effect: eff.id(),
                coefficient: c.coefficients().and_then(|co| co.get(j).cloned()),
                truth: None,
            })
        })
        .map(|f| Found {
            truth: truth(&f.channel, &f.effect),
            ..f
        })
        .collect();
    let missed: Vec<Hidden> = hidden
        .iter()
        .filter(|h| {
            !found
                .iter()
                .any(|f| f.channel == h.channel && f.effect == h.effect)
        })
        .cloned()
        .collect();
    let channel_rms = base
        .inner()
        .channels()
        .iter()
        .zip(model.inner().channels())
        .map(|(b, f)| (f.channel(), b.scores().val_rms, f.scores().val_rms))
        .collect();

    progress("writing the final report");
    let final_dir = out.join("final").join("report");
    let lead = lead(unit, &hidden, &found, &missed);
    let written = write_page(
        &model,
        &records,
        Page {
            baseline: Some((&base, &base_path)),
            lead,
            links: vec![
                (
                    baseline_report.clone(),
                    "The baseline report (before the loop)".into(),
                ),
                (
                    diagnosis_report.clone(),
                    "The diagnosis of the baseline (what the model was missing)".into(),
                ),
                (
                    final_diagnosis_report.clone(),
                    "The diagnosis of this model (what is left)".into(),
                ),
                (
                    final_dir.join("index.html"),
                    "This report, next to its figures".into(),
                ),
            ],
            also_into: Some(out.to_path_buf()),
            diagnosis: Some(DiagnosisExtra {
                diagnosis: last,
                of: "this model (after the loop)".into(),
                min_err,
                page: final_diagnosis_report.clone(),
            }),
            ..Page::new(&model_path, &data)
        },
        &final_dir,
    )?;
    let (final_report, parity) = (written.index, written.parity);
    Ok(UnitDemo {
        record,
        hidden,
        found,
        missed,
        channel_rms,
        parity,
        rounds: e.rounds.len(),
        converged: e.converged,
        baseline_report,
        diagnosis_report,
        final_diagnosis_report,
        final_report,
        index: out.join("index.html"),
    })
}

/// The final page's opening: what was hidden, what the loop found.
fn lead(unit: &Unit, hidden: &[Hidden], found: &[Found], missed: &[Hidden]) -> Vec<String> {
    let hid: Vec<String> = hidden
        .iter()
        .map(|h| format!("{}={} ({} {})", h.channel, h.effect, h.value, h.unit))
        .collect();
    let mut out = vec![format!(
        "The demo on the unit '{}': a simulated vibration test with {} hidden from the ground calibration; the loop (fit, diagnose, add what it names, refit) found:",
        unit.name(),
        hid.join(" and ")
    )];
    for f in found {
        out.push(found_text(f));
    }
    if found.is_empty() {
        out.push("nothing.".into());
    }
    for m in missed {
        out.push(format!(
            "Missed: {}={} (hidden {} {}).",
            m.channel, m.effect, m.value, m.unit
        ));
    }
    out
}

/// One found effect in words, against the truth if it was hidden.
pub fn found_text(f: &Found) -> String {
    let coef = match &f.coefficient {
        Some(c) => format!(
            "{:.4} ± {:.4} {} (95% CI {:.4} to {:.4})",
            c.value, c.se, c.unit, c.ci95[0], c.ci95[1]
        ),
        None => "no interval".into(),
    };
    let truth = match (f.truth, f.covers()) {
        (Some(t), Some(true)) => format!("; hidden {t}, inside the interval"),
        (Some(t), Some(false)) => format!("; hidden {t}, OUTSIDE the interval"),
        (Some(t), None) => format!("; hidden {t}"),
        // A unit file with channels named like the paper's takes the
        // scenario's own paper coefficients too (docs/formats.md, the
        // `[unit]` table): truth.json says whether one holds this effect.
        (None, _) => "; not hidden by the demo: a false alarm, unless the scenario's own coefficients hold it (simulation/truth.json)".into(),
    };
    format!("{}={}: {coef}{truth}.", f.channel, f.effect)
}
