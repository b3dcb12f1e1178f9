//! One run of the loop on a simulated unit, shared by the loop's tests.

use dtg_vib::unit_sensor::{RateReference, UnitEffect, UnitSensor, to_signals};
use nav_sensors::sim::{Scenario, simulate_unit};
use nav_sensors::unit::Unit;
use std::collections::BTreeMap;

/// What one loop found: every (channel, effect) added, the final model's
/// intervals by (channel, effect), and each channel's final validation rms.
#[derive(Debug)]
pub struct Found {
    pub added: Vec<(String, String)>,
    pub intervals: BTreeMap<(String, String), [f64; 2]>,
    pub val_rms: Vec<f64>,
}

/// Simulates `s` on `unit` and runs the loop (the defaults of `explain`)
/// after the simulated ground calibration; `window` names the window's
/// signals, or the library's default (the records' choice) with `None`.
pub fn run(unit: &Unit, s: &Scenario, window: Option<&[&str]>) -> Found {
    let sim = simulate_unit(unit, s).unwrap();
    let sensor = UnitSensor {
        unit: unit.clone(),
        calibration: Some(sim.calibration.clone()),
        rate_reference: RateReference::None,
    };
    let sig = to_signals(&sim.record).unwrap();
    let mut options = sysid::FitOptions::<UnitEffect>::new(unit.gyros().len());
    if let Some(w) = window {
        let names = w.iter().map(|n| n.to_string()).collect();
        options.recipe.preprocess.window = sysid::WindowSpec::new(names, 50).unwrap();
    }
    let e = sysid::explain::explain(
        &sensor,
        &[("r".into(), &sig)],
        &options,
        &Default::default(),
        5,
        &|_| {},
    )
    .unwrap();
    let added = e
        .rounds
        .iter()
        .flat_map(|r| {
            r.added
                .iter()
                .map(|a| (a.channel.clone(), a.effect.clone()))
        })
        .collect();
    let mut intervals = BTreeMap::new();
    for c in e.model.channels() {
        for (k, eff) in c.effects().iter().enumerate() {
            if let Some(co) = c.coefficients() {
                intervals.insert((c.channel(), eff.id()), co[k].ci95);
            }
        }
    }
    let val_rms = e
        .model
        .channels()
        .iter()
        .map(|c| c.scores().val_rms)
        .collect();
    Found {
        added,
        intervals,
        val_rms,
    }
}
