//! The simulator of any unit, the paper's included: vibration, motion and
//! thermal physics producing the unit's gyros
//! (each with its DTG or rate model, in its axes) and accelerometers. The
//! scenario's `[unit]` table gives the gyros' coefficients and hidden
//! effects by channel name and term id ([`super::UnitGyros`]); a channel
//! listed nowhere is an ideal gyro, and a `dtg` channel named like one of
//! the paper's takes `gyros.channels`, so every built-in scenario runs on
//! every unit. Accelerometers on a unit axis take that axis's coefficients
//! (`accels.axes`); others are error-free (noise and servo loop still
//! apply).

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::Vector3;

use super::budget::{Reference, channel_budget};
use super::calibrate::unit_ground_calibration;
use super::engine::{AccelPhysics, GyroPhysics, Run, Stream, run, stream};
use super::error::SimError;
use super::output::{Components, PaperFiles};
use super::predictable;
use super::scenario::{Scenario, ScenarioError};
use super::truth::{UnitChannelTruth, UnitCollinear, UnitHiddenTruth, UnitTruth};
use crate::accel::AccelCoefficients;
use crate::dtg::{DtgInput, DtgTerm};
use crate::files::calibration::{GyroCoefficients, UnitCalibration};
use crate::files::record::Record;
use crate::geometry::{Axis, Channel};
use crate::rate::{RateInput, RateTerm};
use crate::unit::{FileFormat, Gyro, GyroModel, GyroTerm, Unit};
use stats::{rms, std_dev};

/// The result of [`simulate_unit`]: the record (deg/h and g inside; written
/// in the unit's names and units), the calibration a user would have, the
/// truth.
///
/// ```
/// use nav_sensors::sim::{simulate_unit, Scenario};
/// let unit = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let sim = simulate_unit(&unit, &Scenario { duration_s: 1.0, ..Scenario::default() }).unwrap();
/// assert_eq!(sim.record.gyro_names(), ["gx", "gy", "gz"]);
/// // At rest before the shaker starts: az reads 1 g.
/// assert!((sim.record.accel_named("az").unwrap()[0] - 1.0).abs() < 1e-3);
/// ```
#[derive(Debug, Clone)]
pub struct UnitSimulation {
    /// The unit simulated.
    pub unit: Unit,
    /// The record, deg/h and g.
    pub record: Record,
    /// The ground calibration handed to the user.
    pub calibration: UnitCalibration,
    /// Everything used, and the noise floors.
    pub truth: UnitTruth,
    /// Per-sample component series ([`Components`], named by the unit's
    /// channels).
    pub components: Components,
}

impl UnitSimulation {
    /// File names written by [`UnitSimulation::write_dir`] in the unit
    /// formats ([`FileFormat::Unit`]).
    ///
    /// ```
    /// assert!(nav_sensors::sim::UnitSimulation::FILES.contains(&"unit.toml"));
    /// ```
    pub const FILES: [&'static str; 5] = [
        "record.csv",
        "calibration.json",
        "truth.json",
        "scenario.toml",
        "unit.toml",
    ];

    /// The files [`UnitSimulation::write_dir`] writes for `unit`: in its
    /// file formats ([`Unit::file_format`]).
    ///
    /// ```
    /// use nav_sensors::sim::UnitSimulation;
    /// use nav_sensors::unit::Unit;
    /// assert!(UnitSimulation::files(&Unit::paper()).contains(&"components.csv"));
    /// assert!(UnitSimulation::files(&Unit::builtin("tetra").unwrap()).contains(&"unit.toml"));
    /// ```
    pub fn files(unit: &Unit) -> [&'static str; 5] {
        match unit.file_format() {
            FileFormat::Unit => Self::FILES,
            FileFormat::Paper => PaperFiles::FILES,
        }
    }

    /// The per-sample components its files hold (`components.csv` of the
    /// paper's formats; the unit formats write none).
    ///
    /// ```
    /// use nav_sensors::sim::{simulate_unit, Scenario};
    /// use nav_sensors::unit::Unit;
    /// let s = Scenario { duration_s: 1.0, ..Scenario::default() };
    /// assert!(simulate_unit(&Unit::paper(), &s).unwrap().written_components().is_some());
    /// assert!(simulate_unit(&Unit::builtin("triad").unwrap(), &s).unwrap().written_components().is_none());
    /// ```
    pub fn written_components(&self) -> Option<&Components> {
        match self.unit.file_format() {
            FileFormat::Unit => None,
            FileFormat::Paper => Some(&self.components),
        }
    }

    /// The paper unit's simulation in the paper's file shapes (`None` for
    /// a unit whose sensors are not the paper's).
    fn to_paper(&self) -> Option<PaperFiles> {
        Some(PaperFiles {
            record: self.record.clone(),
            calibration: self.calibration.to_paper()?,
            truth: self.truth.to_paper()?,
            components: self.components.clone(),
        })
    }

    /// Writes [`UnitSimulation::files`] into `dir` (created if needed): in
    /// the unit formats, `record.csv` (the unit's column names and units),
    /// `calibration.json`, `truth.json`, `scenario.toml` and `unit.toml`;
    /// in the paper's, `record.csv`, `calibration.json`, `truth.json`,
    /// `components.csv` and `scenario.toml`.
    ///
    /// ```
    /// use nav_sensors::sim::{simulate_unit, Scenario, UnitSimulation};
    /// use nav_sensors::record::Record;
    /// let unit = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let sim = simulate_unit(&unit, &Scenario { duration_s: 1.0, ..Scenario::default() }).unwrap();
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-unit-sim");
    /// sim.write_dir(&dir).unwrap();
    /// for f in UnitSimulation::FILES { assert!(dir.join(f).exists()); }
    /// let text = std::fs::read_to_string(dir.join("record.csv")).unwrap();
    /// assert!(text.starts_with("t,gx,gy,gz,ax,ay,az,temp\n"));
    /// let back = Record::read_with_unit(dir.join("record.csv"), &unit).unwrap();
    /// assert_eq!(back.records.len(), 1);
    /// ```
    pub fn write_dir(&self, dir: impl AsRef<Path>) -> Result<(), SimError> {
        let dir = dir.as_ref();
        let paper = match self.unit.file_format() {
            FileFormat::Unit => None,
            FileFormat::Paper => self.to_paper(),
        };
        if let Some(paper) = paper {
            return paper.write_dir(dir);
        }
        let io = |path: &Path| {
            let path = path.display().to_string();
            move |source| SimError::Io { path, source }
        };
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        self.record
            .write_csv_with_unit(dir.join("record.csv"), &self.unit)?;
        self.calibration.save(dir.join("calibration.json"))?;
        let truth = dir.join("truth.json");
        outfile::write_bytes(&truth, self.truth.to_json()).map_err(io(&truth))?;
        self.truth.scenario.save(dir.join("scenario.toml"))?;
        let unit = dir.join("unit.toml");
        outfile::write_bytes(&unit, self.unit.to_toml()).map_err(io(&unit))?;
        Ok(())
    }
}

/// The scenario's `[unit]` and paper tables resolved against a unit: each
/// gyro's true coefficients, the hidden effects (gyro index, term), and
/// the paper-table entries the unit has no channel for.
struct Resolved {
    gyros: Vec<GyroCoefficients>,
    hidden: Vec<(usize, GyroTerm)>,
    not_applied: Vec<String>,
}

fn resolve(unit: &Unit, s: &Scenario) -> Result<Resolved, ScenarioError> {
    let bad = |key: String, problem: String| ScenarioError::Unit { key, problem };
    let file = unit.file();
    for (table, names, model) in [
        ("rate", s.unit.rate.keys().collect::<Vec<_>>(), "rate"),
        ("dtg", s.unit.dtg.keys().collect(), "dtg"),
    ] {
        for name in names {
            match unit.gyro_index(name) {
                None => {
                    return Err(bad(
                        format!("unit.{table}.{name}"),
                        format!(
                            "{file} has no gyro '{name}' (its gyros: {})",
                            unit.gyro_names().join(", ")
                        ),
                    ));
                }
                Some(k) if unit.gyros()[k].model.name() != model => {
                    return Err(bad(
                        format!("unit.{table}.{name}"),
                        format!(
                            "gyro '{name}' is a \"{}\" gyro in {file}: give its coefficients under unit.{}",
                            unit.gyros()[k].model.name(),
                            unit.gyros()[k].model.name()
                        ),
                    ));
                }
                Some(_) => {}
            }
        }
    }
    let gyros: Vec<GyroCoefficients> = unit
        .gyros()
        .iter()
        .map(|g| match g.model {
            GyroModel::Rate => {
                GyroCoefficients::Rate(s.unit.rate.get(&g.name).copied().unwrap_or_default())
            }
            GyroModel::Dtg { .. } => {
                GyroCoefficients::Dtg(s.unit.dtg.get(&g.name).copied().unwrap_or_else(|| {
                    g.name
                        .parse::<Channel>()
                        .map(|c| s.gyro(c))
                        .unwrap_or_default()
                }))
            }
        })
        .collect();
    let mut hidden = Vec::new();
    let mut not_applied = Vec::new();
    for h in &s.hidden {
        match unit.gyro_index(h.channel.name()) {
            Some(k) if matches!(unit.gyros()[k].model, GyroModel::Dtg { .. }) => {
                hidden.push((k, GyroTerm::Dtg(h.term)));
            }
            _ => not_applied.push(format!(
                "{}={}: {file} has no DTG channel {}",
                h.channel, h.term, h.channel
            )),
        }
    }
    for (i, h) in s.unit.hidden.iter().enumerate() {
        let key = format!("unit.hidden[{i}]");
        let k = unit.gyro_index(&h.channel).ok_or_else(|| {
            bad(
                key.clone(),
                format!(
                    "{file} has no gyro '{}' (its gyros: {})",
                    h.channel,
                    unit.gyro_names().join(", ")
                ),
            )
        })?;
        let term = unit
            .parse_term(k, &h.term)
            .map_err(|e| bad(key.clone(), format!("{}: {e}", h.channel)))?;
        let k_term = unit.gyros()[k]
            .terms()
            .iter()
            .position(|t| *t == term)
            .expect("a term of the model");
        if gyros[k].to_vec()[k_term] == 0.0 {
            return Err(bad(
                key,
                format!(
                    "{h}: its truth coefficient is zero (give it under unit.{}.{})",
                    unit.gyros()[k].model.name(),
                    h.channel
                ),
            ));
        }
        hidden.push((k, term));
    }
    Ok(Resolved {
        gyros,
        hidden,
        not_applied,
    })
}

/// Each accelerometer's physics and true coefficients (zero for one off
/// the unit axes, which is error-free).
fn accel_physics(unit: &Unit, s: &Scenario) -> (Vec<AccelPhysics>, Vec<AccelCoefficients>) {
    unit.accels()
        .iter()
        .map(
            |a| match Axis::ALL.into_iter().find(|x| a.input == x.unit_vector()) {
                Some(axis) => (
                    AccelPhysics::Modelled {
                        axis,
                        coefficients: s.accel(axis),
                    },
                    s.accel(axis),
                ),
                None => (
                    AccelPhysics::Ideal { input: a.input },
                    AccelCoefficients::default(),
                ),
            },
        )
        .unzip()
}

/// Simulates a scenario on any unit: the record, the calibration a user
/// would have and the truth. The same unit and scenario (seed included)
/// always give identical results; on the paper's unit the record is the
/// one the paper's files hold.
///
/// ```
/// use nav_sensors::sim::{simulate_unit, Scenario};
/// use nav_sensors::unit::Unit;
/// let s = Scenario { duration_s: 1.0, ..Scenario::default() };
/// let paper = simulate_unit(&Unit::paper(), &s).unwrap();
/// assert_eq!(paper.record.len(), 50);
/// assert!((paper.record.dt() - 0.02).abs() < 1e-12);
/// // Shaker off at first: az reads 1 g.
/// assert!((paper.record.accel_named("az").unwrap()[0] - 1.0).abs() < 1e-3);
/// let tetra = simulate_unit(&Unit::builtin("tetra").unwrap(), &s).unwrap();
/// assert_eq!(tetra.record.gyro_names(), ["g1", "g2", "g3", "g4"]);
/// ```
pub fn simulate_unit(unit: &Unit, s: &Scenario) -> Result<UnitSimulation, SimError> {
    s.validate()?;
    let resolved = resolve(unit, s)?;
    let gyros: Vec<GyroPhysics> = unit
        .gyros()
        .iter()
        .zip(&resolved.gyros)
        .map(|(g, c)| match (g.dtg_axes(), c) {
            (Some(axes), GyroCoefficients::Dtg(c)) => GyroPhysics::dtg(s, axes, *c),
            (_, GyroCoefficients::Rate(c)) => GyroPhysics::Rate {
                input: g.input,
                coefficients: *c,
            },
            (None, GyroCoefficients::Dtg(_)) => unreachable!("resolved by model"),
        })
        .collect();
    let (accels, accel_truth) = accel_physics(unit, s);
    let Run {
        hr,
        t,
        gyro,
        accel,
        noise,
        temp_meas,
    } = run(s, gyros, &accels)?;
    let temp_name = unit.columns().temperature.clone();
    let record = Record::from_series(
        t,
        unit.gyro_names()
            .iter()
            .map(|n| n.to_string())
            .zip(gyro)
            .collect(),
        unit.accel_names()
            .iter()
            .map(|n| n.to_string())
            .zip(accel)
            .collect(),
        vec![(
            temp_name.clone().unwrap_or_else(|| "temp".to_string()),
            temp_meas.clone(),
        )],
        temp_name,
    )?;
    let calibration = unit_ground_calibration(
        unit,
        s,
        &resolved.gyros,
        &resolved.hidden,
        &accel_truth,
        &mut stream(s.seed, Stream::Calibration),
    );
    let (truth, components) = unit_budget(
        unit,
        s,
        &resolved,
        &calibration,
        &hr,
        &noise,
        &temp_meas,
        record.t(),
    );
    Ok(UnitSimulation {
        unit: unit.clone(),
        record,
        calibration,
        truth,
        components,
    })
}

/// The g and g² weights of a rate gyro on the elementary series: its
/// regressors already are f_x, f_y, f_z and the six products.
fn rate_weights(c: &[f64]) -> [f64; 9] {
    std::array::from_fn(|k| c[RateTerm::SPECIFIC_FORCE[k].index()])
}

/// The regressors of a gyro at what the record shows (rate `w` in deg/h,
/// specific force `f` in g, temperature less the reference), the rate about
/// its input axis a model takes as the reference, and the DTG
/// nonlinearity's drift there (none for a rate gyro).
fn gyro_at_record(
    g: &Gyro,
    truth: &GyroCoefficients,
    w: &Vector3<f64>,
    f: &Vector3<f64>,
    temperature_delta_c: f64,
) -> (Vec<f64>, f64, f64) {
    match (truth, g.dtg_axes()) {
        (GyroCoefficients::Dtg(coefficients), Some(axes)) => {
            let x = DtgInput {
                rate_deg_h: axes.resolve(w),
                specific_force_g: axes.resolve(f),
                temperature_delta_c,
                ..DtgInput::default()
            };
            let wi = x.rate_deg_h.i;
            (
                DtgTerm::regressors(&x).to_vec(),
                wi,
                coefficients.nonlinearity_deg_h(wi),
            )
        }
        _ => {
            let mut x = RateInput::sensed(&g.input, w, f);
            x.temperature_delta_c = temperature_delta_c;
            (RateTerm::regressors(&x).to_vec(), x.rate_i_deg_h, 0.0)
        }
    }
}

/// Each of the unit's residues of per-channel series (unit order): with
/// `std_dev` the noise floor through it, with `rms` what true-coefficient
/// compensation leaves of it, deg/h.
fn per_residue(
    unit: &Unit,
    series: &[Vec<f64>],
    n_out: usize,
    statistic: fn(&[f64]) -> f64,
) -> BTreeMap<String, f64> {
    let coefficients = unit.geometry().residue_coefficients();
    unit.residue_names()
        .iter()
        .enumerate()
        .map(|(r, name)| {
            let combined: Vec<f64> = (0..n_out)
                .map(|n| {
                    (0..series.len())
                        .map(|k| coefficients[(r, k)] * series[k][n])
                        .sum()
                })
                .collect();
            (name.clone(), statistic(&combined))
        })
        .collect()
}

/// The specific-force terms of a gyro's model (term indices, in the
/// order of [`DtgTerm::SPECIFIC_FORCE`] / [`RateTerm::SPECIFIC_FORCE`]):
/// the candidates checked for collinearity.
fn specific_force_terms(g: &Gyro) -> [usize; 9] {
    match g.model {
        GyroModel::Dtg { .. } => DtgTerm::SPECIFIC_FORCE.map(DtgTerm::index),
        GyroModel::Rate => RateTerm::SPECIFIC_FORCE.map(RateTerm::index),
    }
}

/// The truth of a channel's hidden effects: what each adds to the record
/// as a model of the record sees it (`c_k · r_k(x̄)`, pushed as the
/// component `hidden_{channel}_{term}`), its rms and its ratio to the
/// channel's noise floor.
fn hidden_truth(
    g: &Gyro,
    hidden: &[GyroTerm],
    c: &[f64],
    pred: &[Vec<f64>],
    noise_floor: f64,
    components: &mut Components,
) -> Vec<UnitHiddenTruth> {
    let terms = g.terms();
    hidden
        .iter()
        .map(|term| {
            let k = terms
                .iter()
                .position(|t| t == term)
                .expect("a term of the model");
            let visible: Vec<f64> = pred.iter().map(|p| c[k] * p[k]).collect();
            let rms_deg_h = std_dev(&visible);
            components.push(&format!("hidden_{}_{}", g.name, term.id()), visible);
            UnitHiddenTruth {
                channel: g.name.clone(),
                term: term.id().to_string(),
                coefficient: c[k],
                unit: term.unit().to_string(),
                description: term.ieee_name().to_string(),
                rms_deg_h,
                ratio_to_noise_floor: rms_deg_h / noise_floor,
            }
        })
        .collect()
}

/// What one channel's budget gives: its truth, its hidden effects' truth,
/// and the series the residues and the components are built from.
struct ChannelOutcome {
    truth: UnitChannelTruth,
    hidden: Vec<UnitHiddenTruth>,
    floor: Vec<f64>,
    after: Vec<f64>,
}

/// Channel `ch`'s truth and budget (see [`super::budget`]), its
/// components pushed in the paper's order: its hidden effects', then
/// noise, motion, unmodelled, expected, predictable, floor.
#[allow(clippy::too_many_arguments)]
fn channel_outcome(
    unit: &Unit,
    ch: usize,
    s: &Scenario,
    resolved: &Resolved,
    calibration: &UnitCalibration,
    hr: &super::engine::HighRate,
    noise: &[f64],
    temp_meas: &[f64],
    reference: &Reference,
    components: &mut Components,
) -> ChannelOutcome {
    let g = &unit.gyros()[ch];
    let truth = &resolved.gyros[ch];
    let c = truth.to_vec();
    let at_record = |n: usize| {
        let a = hr.accel_ideal_g[n];
        let f = Vector3::new(a[0], a[1], a[2]);
        gyro_at_record(
            g,
            truth,
            &reference.static_rate[n],
            &f,
            temp_meas[n] - s.thermal.reference_c,
        )
    };
    let weights = match g.dtg_axes() {
        Some(axes) => predictable::weights(
            &axes.input,
            &axes.output,
            &axes.spin,
            &c.clone().try_into().expect("18 DTG terms"),
        ),
        None => rate_weights(&c),
    };
    let b = channel_budget(
        hr,
        ch,
        &c,
        noise,
        &reference.elementary,
        &weights,
        at_record,
    );
    let noise_floor = std_dev(&b.floor);
    let terms = g.terms();
    let hidden_here: Vec<GyroTerm> = resolved
        .hidden
        .iter()
        .filter(|(k, _)| *k == ch)
        .map(|(_, t)| *t)
        .collect();
    let hidden = hidden_truth(g, &hidden_here, &c, &b.pred, noise_floor, components);
    let cal = calibration
        .gyros
        .get(&g.name)
        .map_or_else(|| vec![0.0; c.len()], GyroCoefficients::to_vec);
    let counted: Vec<bool> = terms
        .iter()
        .map(|t| t.is_calibrated() && !hidden_here.contains(t))
        .collect();
    let extras = b.extras(
        &hr.level_squared,
        &c,
        &cal,
        &counted,
        &specific_force_terms(g),
    );
    let id = |k: usize| terms[k].id().to_string();
    let truth = UnitChannelTruth {
        channel: g.name.clone(),
        coefficients: *truth,
        noise_floor_deg_h: noise_floor,
        noise_rms_deg_h: std_dev(&b.noise),
        motion_rms_deg_h: rms(&b.motion),
        unmodelled_rms_deg_h: rms(&b.unmodelled),
        predictable_rms_deg_h: rms(&b.predicted),
        after_true_compensation_rms_deg_h: rms(&b.after),
        level_only_noise_floor_deg_h: extras.level_only_floor_deg_h,
        rectification_expected_rms_deg_h: rms(&extras.expected),
        rectification_at_full_level_deg_h: extras
            .at_full
            .iter()
            .map(|&(k, v)| (id(k), v))
            .collect(),
        calibration_error_rms_deg_h: extras.calibration_error_deg_h,
        collinear: extras
            .collinear
            .iter()
            .map(|&(a, b, correlation)| UnitCollinear {
                a: id(a),
                b: id(b),
                correlation,
            })
            .collect(),
    };
    let (floor, after) = b.push_components(components, &g.name, extras.expected);
    ChannelOutcome {
        truth,
        hidden,
        floor,
        after,
    }
}

/// The truth of a unit's simulation and its component series.
#[allow(clippy::too_many_arguments)]
fn unit_budget(
    unit: &Unit,
    s: &Scenario,
    resolved: &Resolved,
    calibration: &UnitCalibration,
    hr: &super::engine::HighRate,
    noise: &[Vec<f64>],
    temp_meas: &[f64],
    t: &[f64],
) -> (UnitTruth, Components) {
    let n_out = temp_meas.len();
    let reference = Reference::of(s, hr);
    let mut components = Components::new(t.to_vec());
    components.push("level_squared", hr.level_squared.clone());
    let mut channels = Vec::new();
    let mut hidden = Vec::new();
    let mut floors = Vec::new();
    let mut after = Vec::new();
    for (ch, noise_ch) in noise.iter().enumerate() {
        let o = channel_outcome(
            unit,
            ch,
            s,
            resolved,
            calibration,
            hr,
            noise_ch,
            temp_meas,
            &reference,
            &mut components,
        );
        channels.push(o.truth);
        hidden.extend(o.hidden);
        floors.push(o.floor);
        after.push(o.after);
    }
    let (earth, gravity) = (reference.earth, reference.gravity);
    let truth = UnitTruth {
        format_version: UnitTruth::FORMAT_VERSION,
        unit: unit.clone(),
        scenario: s.clone(),
        earth_rate_cluster_deg_h: [earth.x, earth.y, earth.z],
        gravity_cluster_g: [gravity.x, gravity.y, gravity.z],
        hidden,
        not_applied: resolved.not_applied.clone(),
        channels,
        residue_noise_floor_deg_h: per_residue(unit, &floors, n_out, std_dev),
        residue_after_true_compensation_rms_deg_h: per_residue(unit, &after, n_out, rms),
    };
    (truth, components)
}
