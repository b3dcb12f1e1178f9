//! The main job on a built-in default: simulate the paper's test (with one
//! effect hidden), fit, compensate, report, then walk the diagnosis loop —
//! diagnose, add what it names, refit — and show the error fall.

use crate::apply::Applied;
use crate::diagnose::{DiagnoseOptions, Diagnosis};
use crate::effects::ChannelEffect;
use crate::error::DtgVibError;
use crate::explain::diagnose;
use crate::fit::{FitOptions, FitStage, fit};
use crate::model::CompensationModel;
use crate::parity::ResidueStats;
use crate::report::{
    Baseline, DiagnosisExtra, NoiseFloor, Provenance, ReportExtras, build_report,
    write_diagnosis_report, write_report,
};
use nav_sensors::geometry::Channel;
use nav_sensors::sim::{Scenario, simulate};
use std::path::{Path, PathBuf};

/// A step of the demo, for progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DemoStep {
    /// Simulating the vibration test.
    Simulate,
    /// Fitting the baseline model.
    FitBaseline,
    /// Writing the baseline report.
    ReportBaseline,
    /// Diagnosing the baseline.
    Diagnose,
    /// Refitting with the suggested effects.
    Refit,
    /// Diagnosing the refit (where it still fails, for the final report).
    DiagnoseFinal,
    /// Writing the final report.
    ReportFinal,
}

impl std::fmt::Display for DemoStep {
    /// What the user reads while the step runs.
    ///
    /// ```
    /// assert_eq!(dtg_vib::demo::DemoStep::FitBaseline.to_string(), "fitting the baseline model");
    /// ```
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            DemoStep::Simulate => "simulating the vibration test",
            DemoStep::FitBaseline => "fitting the baseline model",
            DemoStep::ReportBaseline => "writing the baseline report",
            DemoStep::Diagnose => "diagnosing the baseline",
            DemoStep::Refit => "refitting with the suggested effects",
            DemoStep::DiagnoseFinal => "diagnosing the refit",
            DemoStep::ReportFinal => "writing the final report",
        })
    }
}

/// What the demo found and where it wrote it.
#[derive(Debug, Clone)]
pub struct DemoSummary {
    /// The output directory.
    pub out: PathBuf,
    /// The simulated record.
    pub record: PathBuf,
    /// The baseline report page (the paper's procedure).
    pub baseline_report: PathBuf,
    /// The diagnosis page.
    pub diagnosis_report: PathBuf,
    /// The final report page (after adding the suggested effects).
    pub final_report: PathBuf,
    /// `out/index.html`: the final report, linking the others; the page to open first.
    pub index: PathBuf,
    /// Residue rms before/after the baseline compensation, validation rows.
    pub baseline_residues: Vec<ResidueStats>,
    /// Residue rms before/after the final compensation, validation rows.
    pub final_residues: Vec<ResidueStats>,
    /// What the simulation hid, as `CHANNEL=term`.
    pub hidden: Vec<String>,
    /// What the diagnosis suggested.
    pub suggested: Vec<ChannelEffect>,
    /// Per channel: validation rms of the baseline and of the final model, deg/h.
    pub channel_rms: Vec<(Channel, f64, f64)>,
    /// The diagnosis of the baseline.
    pub diagnosis: Diagnosis,
}

/// Runs the demo into `out` (created if needed).
pub fn run(out: &Path, progress: &(dyn Fn(DemoStep) + Sync)) -> Result<DemoSummary, DtgVibError> {
    mkdir(out)?;

    progress(DemoStep::Simulate);
    let scenario = Scenario::demo();
    let sim = simulate(&scenario)?;
    let sim_dir = out.join("simulation");
    sim.write_dir(&sim_dir)?;
    let record_path = sim_dir.join("record.csv");

    progress(DemoStep::FitBaseline);
    let options = FitOptions::default();
    let (baseline, applied_base) = fit_and_save(&sim, &options, &out.join("baseline"))?;

    progress(DemoStep::ReportBaseline);
    let base_report = write_report(
        &baseline,
        &applied_base,
        &sim.record,
        "simulated (built-in demo scenario)",
        None,
        &out.join("baseline").join("report"),
    )?;

    progress(DemoStep::Diagnose);
    let diag_options = DiagnoseOptions::default();
    let diagnosis = diagnose(&baseline, &sim.record, &diag_options)?;
    let diag_page = write_diagnosis_report(
        &diagnosis,
        diag_options.rank.min_err(),
        &out.join("diagnosis"),
    )?;
    let suggested = suggestions(&diagnosis)?;

    progress(DemoStep::Refit);
    let refit_options = FitOptions {
        add: suggested.clone(),
        ..options
    };
    let (fitted, applied_final) = fit_and_save(&sim, &refit_options, &out.join("final"))?;

    progress(DemoStep::DiagnoseFinal);
    // Where the final model still fails, for the final page: a diagnosis of
    // the refit, with a page of its own.
    let final_diagnosis = diagnose(&fitted, &sim.record, &diag_options)?;
    let final_diag_page = write_diagnosis_report(
        &final_diagnosis,
        diag_options.rank.min_err(),
        &out.join("final").join("diagnosis"),
    )?;

    progress(DemoStep::ReportFinal);
    let final_dir = out.join("final").join("report");
    let allan = crate::allan::AllanAnalysis::new(&sim.record, Some(&fitted), 0.683)?;
    let provenance = Provenance::of_this_process([
        ("data", record_path.clone()),
        ("calibration", sim_dir.join("calibration.json")),
        ("baseline model", out.join("baseline").join("model.json")),
        ("model", out.join("final").join("model.json")),
    ]);
    let links = Links {
        baseline_report: base_report.index.clone(),
        diagnosis: diag_page.clone(),
        final_diagnosis: final_diag_page.clone(),
        final_report: final_dir.join("index.html"),
    };
    let extras = final_extras(
        &links,
        &provenance,
        &allan,
        &final_diagnosis,
        diag_options.rank.min_err(),
        &sim.components,
    );
    let (final_report, page) = build_report(
        &fitted,
        &applied_final,
        &sim.record,
        "simulated (built-in demo scenario), refitted with the diagnosed effects",
        Some(Baseline {
            label: "baseline",
            model: &baseline,
            applied: &applied_base,
        }),
        &extras,
        &final_dir,
    )?;
    page.write(&final_dir)?;
    // The final report again as `out/index.html`, its figures linked from
    // final/report/: the page to open first.
    let index = page.write(out)?;

    Ok(DemoSummary {
        out: out.to_path_buf(),
        record: record_path,
        baseline_report: base_report.index,
        diagnosis_report: diag_page,
        final_report: final_report.index,
        index,
        baseline_residues: base_report.residues,
        final_residues: final_report.residues,
        hidden: scenario
            .hidden
            .iter()
            .map(|h| format!("{}={}", h.channel, h.term))
            .collect(),
        suggested,
        channel_rms: channel_rms(&baseline, &fitted),
        diagnosis,
    })
}

/// Creates a directory (and its parents), naming it on failure.
fn mkdir(p: &Path) -> Result<(), DtgVibError> {
    std::fs::create_dir_all(p).map_err(|source| DtgVibError::Output {
        path: p.to_path_buf(),
        source,
    })
}

/// Fits the simulated record, saves the model as `dir/model.json` and
/// applies it to the record.
fn fit_and_save(
    sim: &nav_sensors::sim::Simulation,
    options: &FitOptions,
    dir: &Path,
) -> Result<(CompensationModel, Applied), DtgVibError> {
    let model = fit(
        &sim.record,
        Some(&sim.calibration),
        options,
        &|_: FitStage| {},
    )?;
    mkdir(dir)?;
    model.save(dir.join("model.json"))?;
    let applied = Applied::new(&model, &sim.record)?;
    Ok((model, applied))
}

/// Every effect a diagnosis suggests, on its channel.
fn suggestions(diagnosis: &Diagnosis) -> Result<Vec<ChannelEffect>, DtgVibError> {
    diagnosis
        .channels
        .iter()
        .flat_map(|c| c.suggested.iter().map(move |id| (c.channel, id)))
        .map(|(channel, id)| {
            Ok(ChannelEffect {
                channel,
                effect: id.parse()?,
            })
        })
        .collect()
}

/// The pages the final report links to.
struct Links {
    baseline_report: PathBuf,
    diagnosis: PathBuf,
    final_diagnosis: PathBuf,
    final_report: PathBuf,
}

/// What the final page shows beyond the model and the record: where it came
/// from, the Allan analysis, the other pages, the refit's own diagnosis and
/// the simulator's noise floor.
fn final_extras<'a>(
    links: &Links,
    provenance: &'a Provenance,
    allan: &'a crate::allan::AllanAnalysis,
    final_diagnosis: &'a Diagnosis,
    min_err: f64,
    components: &'a nav_sensors::sim::Components,
) -> ReportExtras<'a> {
    ReportExtras {
        provenance: Some(provenance),
        allan: Some(allan),
        links: vec![
            (
                links.baseline_report.clone(),
                "The baseline report (the paper's procedure, before the diagnosis)".into(),
            ),
            (
                links.diagnosis.clone(),
                "The diagnosis of the baseline (what the model was missing)".into(),
            ),
            (
                links.final_diagnosis.clone(),
                "The diagnosis of this model (what is left after the refit)".into(),
            ),
            (
                links.final_report.clone(),
                "This report, next to its figures".into(),
            ),
        ],
        diagnosis: Some(DiagnosisExtra {
            diagnosis: final_diagnosis,
            of: "this model (the refit)".into(),
            min_err,
            page: links.final_diagnosis.clone(),
        }),
        noise_floor: floor_series(components).map(|per_sample| NoiseFloor {
            per_sample: per_sample.to_vec(),
            source: "the simulator's per-sample noise floor (the X_floor … Z1_floor series of simulation/components.csv; truth.json's noise_floor_deg_h is their rms at the output rate): sensor noise, the fixture's true rocking, and what no function of the 50-Hz accelerations can predict of the high-rate effects".into(),
        }),
        ..ReportExtras::default()
    }
}

/// The simulator's per-sample noise floor of each channel (`X_floor` …).
fn floor_series(c: &nav_sensors::sim::Components) -> Option<[&[f64]; 6]> {
    let mut out: [&[f64]; 6] = [&[]; 6];
    for ch in Channel::ALL {
        out[ch.index()] = c.get(&format!("{}_floor", ch.name()))?;
    }
    Some(out)
}

fn channel_rms(before: &CompensationModel, after: &CompensationModel) -> Vec<(Channel, f64, f64)> {
    before
        .channels()
        .iter()
        .zip(after.channels())
        .map(|(b, a)| (b.channel(), b.scores().val_rms, a.scores().val_rms))
        .collect()
}
