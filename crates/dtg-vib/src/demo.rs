//! The main job on a built-in default, for any unit: simulate a vibration
//! test with effects hidden from the unit's ground calibration, fit the
//! baseline (bias and the network), diagnose it, refit with every effect
//! the diagnosis names, diagnose the refit (what is left), and write the
//! pages — the baseline's, the diagnoses', and the final one linking them,
//! again as `out/index.html`.
//!
//! The test suits the unit (issue 22 §6): the paper's unit the paper's
//! Z-axis random test with channel Y1's temperature sensitivity hidden
//! (`scenarios/demo.toml`); `tetra` a g-sensitivity along y on g2 and a
//! temperature sensitivity on g3 in the tri-axial test; `triad` a
//! g-sensitivity along y on gx in a vibration test along z with the
//! fixture's cross-axis motion on y (a g² along z would be a function of
//! the az windows the network sees, and test nothing); `dual-triad` a
//! g-sensitivity along x on gx2. Any other unit gets a g-sensitivity along
//! y on its first rate gyro (or g_S on its first DTG axis), in the
//! tri-axial test, or the z test for three gyros. Each case's record
//! length and seed are those `tests/unit_loop.rs` accepts.

use crate::error::DtgVibError;
use crate::page::{Page, Parity, write_page};
use crate::report::{ChannelWording, DiagnosisExtra, NoiseFloor, write_diagnosis_report_of};
use crate::unit_sensor::{
    Applied, ResidueStats, UnitEffect, UnitModel, UnitSensor, default_window_signals, to_signals,
};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::geometry::Axis;
use nav_sensors::record::Record;
use nav_sensors::sim::{Components, Scenario, UnitHiddenEffect, simulate_unit};
use nav_sensors::unit::{GyroModel, Unit};
use nav_sensors::vibration::Drive;
use std::path::{Path, PathBuf};
use sysid::diagnose::{DiagnoseOptions, Diagnosis};
use sysid::inference::Coefficient;
use sysid::{Sensor, Signals, WindowSpec};

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
    pub unit: String,
}

impl Hidden {
    /// A hidden term with its true coefficient: the loop names a
    /// temperature sensitivity by its column, `col:temp`.
    fn new(channel: &str, term: &str, value: f64, unit: &str) -> Self {
        Self {
            channel: channel.into(),
            term: term.into(),
            effect: match term {
                "temp" => "col:temp".into(),
                t => t.into(),
            },
            value,
            unit: unit.into(),
        }
    }
}

/// The demo's test on `unit`: the scenario, with what it hides on the
/// unit's own channels.
pub fn scenario(unit: &Unit) -> Result<Scenario, DtgVibError> {
    let is = |name: &str| Unit::builtin(name).is_ok_and(|b| &b == unit);
    if is("paper") {
        return Ok(Scenario::demo());
    }
    let (hidden, along_z, seed) = if is("tetra") {
        (vec![("g2", "g_y", 0.5), ("g3", "temp", 0.05)], false, 31)
    } else if is("triad") {
        (vec![("gx", "g_y", 2.0)], true, 32)
    } else if is("dual-triad") {
        (vec![("gx2", "g_x", 0.5)], false, 33)
    } else {
        let g = &unit.gyros()[0];
        let term = match g.model {
            GyroModel::Rate => "g_y",
            GyroModel::Dtg { .. } => "g_S",
        };
        (
            vec![(g.name.as_str(), term, 0.5)],
            unit.gyros().len() == 3,
            31,
        )
    };
    let mut s = Scenario::triaxial_hidden();
    s.name = "demo".into();
    s.hidden.clear();
    s.duration_s = 60.0;
    s.seed = seed;
    for (channel, term, value) in hidden {
        let is_dtg = unit
            .gyro_index(channel)
            .is_some_and(|k| matches!(unit.gyros()[k].model, GyroModel::Dtg { .. }));
        if is_dtg {
            // The demo's own ids (g_S): they parse.
            let t = term.parse().expect("the demo's DTG term id parses");
            s.unit.dtg.entry(channel.into()).or_default().set(t, value);
        } else {
            let t: nav_sensors::rate::RateTerm =
                term.parse().expect("the demo's rate term ids parse");
            s.unit.rate.entry(channel.into()).or_default().set(t, value);
        }
        s.unit.hidden.push(UnitHiddenEffect {
            channel: channel.into(),
            term: term.into(),
        });
    }
    if along_z {
        shake_along_z(&mut s);
    }
    Ok(s)
}

/// The tri-axial test made a test along z: no drive on x, the drive on y
/// 10 dB down (the fixture's cross-axis motion, independent of z's), so
/// that a g-sensitivity to y is not a function of the az windows.
///
/// ```
/// let mut s = nav_sensors::sim::Scenario::triaxial_hidden();
/// dtg_vib::demo::shake_along_z(&mut s);
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

/// A simulated test: the record, the calibration handed to the user, what
/// was hidden, and (where the simulator gives them) the per-sample noise
/// floors by series name (`X_floor`, …).
struct Simulated {
    record: Record,
    calibration: UnitCalibration,
    hidden: Vec<Hidden>,
    components: Option<Components>,
}

/// Simulates `s` on `unit` and writes its files into `dir`, in the unit's
/// file formats; the noise floors the final page compares the residual
/// with are the components those files hold (the paper's formats write
/// them).
fn simulate_into(unit: &Unit, s: &Scenario, dir: &Path) -> Result<Simulated, DtgVibError> {
    let sim = simulate_unit(unit, s)?;
    sim.write_dir(dir)?;
    let hidden = sim
        .truth
        .hidden
        .iter()
        .map(|h| Hidden::new(&h.channel, &h.term, h.coefficient, &h.unit))
        .collect();
    Ok(Simulated {
        components: sim.written_components().cloned(),
        record: sim.record,
        calibration: sim.calibration,
        hidden,
    })
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

/// What the demo is told: the window's signals (`None`: the unit's
/// accelerometer along z, [`default_window_signals`]; `Some(["auto"])`:
/// chosen from the record, as `fit --window-signals auto`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DemoOptions {
    /// The window's signals.
    pub window_signals: Option<Vec<String>>,
}

/// What the demo found and where it wrote it.
#[derive(Debug, Clone)]
pub struct Demo {
    /// The simulated record.
    pub record: PathBuf,
    /// What was hidden.
    pub hidden: Vec<Hidden>,
    /// Residue rms before/after the baseline compensation, validation rows.
    pub baseline_residues: Vec<ResidueStats>,
    /// The diagnosis of the baseline.
    pub diagnosis: Diagnosis<String, Axis>,
    /// What the refit added, as (channel, effect id).
    pub added: Vec<(String, String)>,
    /// Every effect of the final model.
    pub found: Vec<Found>,
    /// Hidden effects the loop did not add.
    pub missed: Vec<Hidden>,
    /// Per channel: validation rms of the baseline and of the final model, deg/h.
    pub channel_rms: Vec<(String, f64, f64)>,
    /// Residue rms before/after the final compensation, validation rows.
    pub final_residues: Vec<ResidueStats>,
    /// The residues and fault detection of the final model, every sample.
    pub parity: Parity,
    /// Fits the loop made (the baseline, and the refit if anything was added).
    pub rounds: usize,
    /// Whether the refit's diagnosis suggested nothing new.
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

/// The fit options of the demo: the command line's (the network's input and
/// prediction smoother chosen), 50-sample windows of `signals`.
fn fit_options(
    sensor: &UnitSensor,
    named: &[(String, &Signals)],
    signals: &Option<Vec<String>>,
) -> Result<sysid::FitOptions<UnitEffect>, DtgVibError> {
    let mut options = sysid::FitOptions::<UnitEffect>::new(sensor.unit.gyros().len());
    options.recipe.settings.choice = Some(sysid::fit::ModelChoice::default());
    options.recipe.preprocess.window = match signals.as_deref() {
        Some([auto]) if auto == "auto" => sysid::choose_window_signals(sensor, named)?.window(50),
        Some(s) => WindowSpec::new(s.to_vec(), 50),
        None => WindowSpec::new(default_window_signals(&sensor.unit), 50),
    }
    .map_err(sysid::SysidError::from)?;
    Ok(options)
}

/// A fitted model saved as `dir/model.json` and applied to its record.
struct Fitted {
    model: UnitModel,
    path: PathBuf,
    applied: Applied,
}

fn fit_and_save(
    sensor: &UnitSensor,
    named: &[(String, &Signals)],
    records: &[(String, Record)],
    options: &sysid::FitOptions<UnitEffect>,
    dir: &Path,
) -> Result<Fitted, DtgVibError> {
    let (model, _) = sysid::fit_records(sensor, named, options, &|_| {})?;
    let model = UnitModel::of(model);
    mkdir(dir)?;
    let path = dir.join("model.json");
    model.save(&path)?;
    let borrowed: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    let applied = Applied::new(&model, &borrowed)?;
    Ok(Fitted {
        model,
        path,
        applied,
    })
}

impl Fitted {
    /// The same model saved as `dir/model.json` too (the final model when
    /// nothing was added), applied again.
    fn saved_again(&self, dir: &Path, records: &[(String, Record)]) -> Result<Self, DtgVibError> {
        mkdir(dir)?;
        let path = dir.join("model.json");
        self.model.save(&path)?;
        let borrowed: Vec<(String, &Record)> =
            records.iter().map(|(n, r)| (n.clone(), r)).collect();
        Ok(Self {
            model: self.model.clone(),
            path,
            applied: Applied::new(&self.model, &borrowed)?,
        })
    }
}

/// What the refit is told: the unit's plug-in, the record, the options
/// with the effects added, the diagnosis's thresholds.
struct Refit<'a> {
    sensor: &'a UnitSensor,
    named: &'a [(String, &'a Signals)],
    records: &'a [(String, Record)],
    options: &'a sysid::FitOptions<UnitEffect>,
    diagnose: &'a DiagnoseOptions,
}

impl Refit<'_> {
    /// Fits with the additions into `dir` and diagnoses the refit.
    fn run(
        &self,
        dir: &Path,
        progress: &(dyn Fn(&str) + Sync),
    ) -> Result<(Fitted, Diagnosis<String, Axis>), DtgVibError> {
        let f = fit_and_save(self.sensor, self.named, self.records, self.options, dir)?;
        progress("diagnosing the refit");
        let d = sysid::explain::diagnose_records(f.model.inner(), self.named, self.diagnose)?;
        Ok((f, d))
    }
}

/// Runs the demo on `unit` into `out`, saying each step to `progress`.
pub fn run(
    unit: &Unit,
    demo: &DemoOptions,
    out: &Path,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Demo, DtgVibError> {
    mkdir(out)?;
    progress("simulating the vibration test");
    let s = scenario(unit)?;
    let sim_dir = out.join("simulation");
    let sim = simulate_into(unit, &s, &sim_dir)?;
    let record = sim_dir.join("record.csv");
    let sensor = UnitSensor {
        calibration: Some(sim.calibration.clone()),
        ..UnitSensor::new(unit.clone())
    };
    let signals = to_signals(&sim.record)?;
    let name = record.display().to_string();
    let named = [(name.clone(), &signals)];
    let records = [(name, sim.record.clone())];
    let mut options = fit_options(&sensor, &named, &demo.window_signals)?;

    progress("fitting the baseline model");
    let base = fit_and_save(&sensor, &named, &records, &options, &out.join("baseline"))?;
    let data = [record.clone()];
    let source = format!("simulated (built-in {} scenario)", s.name);
    progress("writing the baseline report");
    let page = Page {
        lead: vec![BASELINE_LEAD.to_string()],
        source: Some(source.clone()),
        ..Page::new(&base.path, &data)
    };
    let baseline_report =
        write_page(&base.model, &records, page, &out.join("baseline/report"))?.index;

    progress("diagnosing the baseline");
    let diagnose = DiagnoseOptions::default();
    let wording = ChannelWording::of_unit(unit);
    let min_err = diagnose.rank.min_err();
    let diagnosis = sysid::explain::diagnose_records(base.model.inner(), &named, &diagnose)?;
    let diagnosis_report =
        write_diagnosis_report_of(&diagnosis, min_err, &wording, &out.join("diagnosis"))?;
    let added = add_suggestions(&sensor, &diagnosis, &mut options)?;

    progress("refitting with the suggested effects");
    let final_dir = out.join("final");
    let (fitted, final_diagnosis) = match added.is_empty() {
        // Nothing to add: the baseline is the final model.
        true => (base.saved_again(&final_dir, &records)?, diagnosis.clone()),
        false => Refit {
            sensor: &sensor,
            named: &named,
            records: &records,
            options: &options,
            diagnose: &diagnose,
        }
        .run(&final_dir, progress)?,
    };
    let final_diagnosis_dir = final_dir.join("diagnosis");
    let final_diagnosis_report =
        write_diagnosis_report_of(&final_diagnosis, min_err, &wording, &final_diagnosis_dir)?;
    let converged = nothing_new(&final_diagnosis, &options);

    progress("writing the final report");
    let found = found(&fitted.model, &sim.hidden);
    let missed = missed(&sim.hidden, &found);
    let report_dir = final_dir.join("report");
    let noise_floor = noise_floor(&sim, &sensor);
    let written = write_page(
        &fitted.model,
        &records,
        Page {
            files: vec![("calibration".into(), sim_dir.join("calibration.json"))],
            baseline: Some((&base.model, &base.path)),
            lead: lead(unit, &sim.hidden, &found, &missed),
            links: links(
                [&baseline_report, &diagnosis_report, &final_diagnosis_report],
                &report_dir,
            ),
            also_into: Some(out.to_path_buf()),
            diagnosis: Some(DiagnosisExtra {
                diagnosis: &final_diagnosis,
                of: REFIT.into(),
                min_err,
                page: final_diagnosis_report.clone(),
            }),
            noise_floor,
            source: Some(format!("{source}, refitted with the diagnosed effects")),
            ..Page::new(&fitted.path, &data)
        },
        &report_dir,
    )?;
    let final_report = written.index;
    let channel_rms = channel_rms(&base.model, &fitted.model);
    Ok(Demo {
        record,
        baseline_residues: base.applied.validation_residues(),
        final_residues: fitted.applied.validation_residues(),
        parity: written.parity,
        hidden: sim.hidden,
        diagnosis,
        rounds: if added.is_empty() { 1 } else { 2 },
        added,
        found,
        missed,
        channel_rms,
        converged,
        baseline_report,
        diagnosis_report,
        final_diagnosis_report,
        final_report,
        index: out.join("index.html"),
    })
}

/// Whether the diagnosis suggests nothing the options lack.
fn nothing_new(d: &Diagnosis<String, Axis>, options: &sysid::FitOptions<UnitEffect>) -> bool {
    d.channels.iter().enumerate().all(|(k, c)| {
        let have: Vec<String> = options
            .recipe
            .effects_of(k)
            .iter()
            .map(|e| e.id())
            .collect();
        c.suggested.iter().all(|id| have.contains(id))
    })
}

/// The hidden effects the final model lacks.
fn missed(hidden: &[Hidden], found: &[Found]) -> Vec<Hidden> {
    hidden
        .iter()
        .filter(|h| {
            !found
                .iter()
                .any(|f| f.channel == h.channel && f.effect == h.effect)
        })
        .cloned()
        .collect()
}

/// Each channel's per-sample noise floor, where the simulator gave them.
fn noise_floor<'a>(sim: &'a Simulated, sensor: &UnitSensor) -> Option<NoiseFloor<'a>> {
    let c = sim.components.as_ref()?;
    let floors = sensor
        .channels()
        .iter()
        .map(|ch| c.get(&format!("{ch}_floor")))
        .collect::<Option<Vec<&[f64]>>>()?;
    Some(NoiseFloor {
        per_sample: floors,
        source: NOISE_FLOOR.to_string(),
    })
}

/// Per channel: validation rms of the baseline and of the final model.
fn channel_rms(base: &UnitModel, fitted: &UnitModel) -> Vec<(String, f64, f64)> {
    base.inner()
        .channels()
        .iter()
        .zip(fitted.inner().channels())
        .map(|(b, f)| (f.channel(), b.scores().val_rms, f.scores().val_rms))
        .collect()
}

/// What the final page's inline diagnosis is of.
const REFIT: &str = "this model (the refit)";

/// The baseline page's opening paragraph.
const BASELINE_LEAD: &str = "The baseline: bias and the network over the accelerometers' windows, no physical effect (the demo's first fit).";

/// Where the final page's noise floor comes from.
const NOISE_FLOOR: &str = "the simulator's per-sample noise floor (the X_floor … Z1_floor series of simulation/components.csv; truth.json's noise_floor_deg_h is their rms at the output rate): sensor noise, the fixture's true rocking, and what no function of the 50-Hz accelerations can predict of the high-rate effects";

/// The pages the final page links to.
fn links(pages: [&Path; 3], report_dir: &Path) -> Vec<(PathBuf, String)> {
    let [baseline, diagnosis, final_diagnosis] = pages;
    vec![
        (
            baseline.to_path_buf(),
            "The baseline report (bias and the network, before the diagnosis)".into(),
        ),
        (
            diagnosis.to_path_buf(),
            "The diagnosis of the baseline (what the model was missing)".into(),
        ),
        (
            final_diagnosis.to_path_buf(),
            "The diagnosis of this model (what is left after the refit)".into(),
        ),
        (
            report_dir.join("index.html"),
            "This report, next to its figures".into(),
        ),
    ]
}

/// Every effect the diagnosis suggests that the options lack, added to its
/// channel's effects; returns what was added, as (channel, effect id).
fn add_suggestions(
    sensor: &UnitSensor,
    d: &Diagnosis<String, Axis>,
    options: &mut sysid::FitOptions<UnitEffect>,
) -> Result<Vec<(String, String)>, DtgVibError> {
    let mut added = Vec::new();
    for (k, c) in d.channels.iter().enumerate() {
        for id in &c.suggested {
            let e = sensor
                .parse_effect(k, id)
                .map_err(sysid::SysidError::Sensor)?;
            if !options.recipe.effects[k].contains(&e) {
                options.recipe.effects[k].push(e);
                added.push((c.channel.clone(), id.clone()));
            }
        }
    }
    Ok(added)
}

/// Every effect of `model`, against its hidden value if it was hidden.
fn found(model: &UnitModel, hidden: &[Hidden]) -> Vec<Found> {
    let truth = |channel: &str, effect: &str| {
        hidden
            .iter()
            .find(|h| h.channel == channel && h.effect == effect)
            .map(|h| h.value)
    };
    model
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
        .collect()
}

/// The final page's opening: what was hidden, what the loop found.
fn lead(unit: &Unit, hidden: &[Hidden], found: &[Found], missed: &[Hidden]) -> Vec<String> {
    let mut out = vec![format!(
        "The demo on the unit '{}': a simulated vibration test with {} hidden from the ground calibration; the loop (fit, diagnose, add what it names, refit) found:",
        unit.name(),
        hidden_text(hidden).join(" and ")
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

/// Each hidden effect as `CHANNEL=ID (VALUE UNIT)`.
pub fn hidden_text(hidden: &[Hidden]) -> Vec<String> {
    hidden
        .iter()
        .map(|h| format!("{}={} ({} {})", h.channel, h.effect, h.value, h.unit))
        .collect()
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
