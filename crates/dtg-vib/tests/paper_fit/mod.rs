//! The paper's unit through the one plug-in ([`UnitSensor`] of the built-in
//! `paper` unit) for the library tests: simulate, fit with the paper's fit
//! defaults (the loop's, with the network input and prediction smoother
//! chosen, as `fit --input auto --smoother auto`), check and diagnose as
//! the commands do.

#![allow(dead_code)] // each test file uses its share

use dtg_vib::unit_sensor::check::{DEFAULT_OUTSIDE_THRESHOLD, TransferCheck, check};
use dtg_vib::unit_sensor::{Applied, RateReference, UnitEffect, UnitModel, UnitSensor, to_signals};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, UnitSimulation, simulate_unit};
use nav_sensors::unit::Unit;
use sysid::{Model, Prepared, Sensor, Signals};

/// A diagnosis of the paper unit's channels.
pub type Diagnosis = sysid::diagnose::Diagnosis<String, <UnitSensor as Sensor>::Axis>;

/// The paper's unit simulated on `s`.
pub fn simulate(s: &Scenario) -> UnitSimulation {
    simulate_unit(&Unit::paper(), s).unwrap()
}

/// The paper's unit after `calibration`, no rate reference.
pub fn sensor(calibration: Option<&UnitCalibration>) -> UnitSensor {
    UnitSensor {
        unit: Unit::paper(),
        calibration: calibration.cloned(),
        rate_reference: RateReference::None,
    }
}

/// The paper's fit defaults: the loop's (the window's signals chosen from
/// the records), with the network input and prediction smoother chosen.
pub fn options() -> sysid::FitOptions<UnitEffect> {
    let mut o = sysid::FitOptions::<UnitEffect>::new(6);
    o.recipe.settings.choice = Some(sysid::fit::ModelChoice::default());
    o
}

/// `ids` (CHANNEL=EFFECT, as `--add-effect`) added to `options`.
pub fn add(options: &mut sysid::FitOptions<UnitEffect>, ids: &[&str]) {
    let unit = Unit::paper();
    let s = sensor(None);
    for id in ids {
        let (channel, effect) = id.split_once('=').unwrap();
        let k = unit
            .gyro_names()
            .iter()
            .position(|n| *n == channel)
            .unwrap();
        options.recipe.effects[k].push(s.parse_effect(k, effect).unwrap());
    }
}

/// The records as the loop reads them.
pub fn signals(records: &[(String, &Record)]) -> Vec<(String, Signals)> {
    records
        .iter()
        .map(|(n, r)| (n.clone(), to_signals(r).unwrap()))
        .collect()
}

/// Borrowed names and signals.
pub fn named(owned: &[(String, Signals)]) -> Vec<(String, &Signals)> {
    owned.iter().map(|(n, s)| (n.clone(), s)).collect()
}

/// The paper unit's model of one record after `calibration`.
pub fn fit(
    record: &Record,
    calibration: Option<&UnitCalibration>,
    options: &sysid::FitOptions<UnitEffect>,
) -> UnitModel {
    let signals = to_signals(record).unwrap();
    let model = sysid::fit::fit(&sensor(calibration), &signals, options, &|_| {});
    UnitModel::of(model.unwrap())
}

/// The paper unit's model of several records after `calibration`, and the
/// records as it reads them.
pub fn fit_records(
    records: &[(String, &Record)],
    calibration: Option<&UnitCalibration>,
    options: &sysid::FitOptions<UnitEffect>,
) -> (UnitModel, Prepared<UnitSensor>) {
    let owned = signals(records);
    let s = sensor(calibration);
    let (model, prepared) = sysid::fit::fit_records(&s, &named(&owned), options, &|_| {}).unwrap();
    (UnitModel::of(model), prepared)
}

/// `check` of `model` on `record`, with the default outside threshold.
pub fn checked(model: &UnitModel, record: &Record) -> TransferCheck {
    let applied = Applied::unsplit(model, &[("r".to_string(), record)]).unwrap();
    check(model, &applied, DEFAULT_OUTSIDE_THRESHOLD).unwrap()
}

/// `diagnose` of `model` on `records`.
pub fn diagnose_records(
    model: &Model<UnitSensor>,
    records: &[(String, &Record)],
    options: &sysid::diagnose::DiagnoseOptions,
) -> Diagnosis {
    let owned = signals(records);
    sysid::explain::diagnose_records(model, &named(&owned), options).unwrap()
}
