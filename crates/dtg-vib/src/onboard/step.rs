//! A causal model run over a record sample by sample through the
//! `dtg-onboard` evaluator, as a flight computer would: what `compensate`
//! does with a causal model, and what the exported C is checked against.

use super::error::ExportError;
use super::tables::{Tables, tables};
use crate::error::DtgVibError;
use crate::unit_sensor::model::UnitModel;
use nav_sensors::record::Record;

/// A record run through the onboard evaluator, from the first sample with
/// a full window on: per channel (the unit's gyros) and per accelerometer,
/// in the unit's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Stepped {
    /// Record sample of the first output.
    pub first_sample: usize,
    /// Compensated rates per channel, deg/h.
    pub rate_deg_h: Vec<Vec<f64>>,
    /// Predicted errors per channel, deg/h.
    pub error_deg_h: Vec<Vec<f64>>,
    /// Calibrated accelerations per accelerometer, g.
    pub accel_g: Vec<Vec<f64>>,
}

/// Runs a causal model over one segment of a log read with its unit (deg/h
/// and g) sample by sample with the `dtg-onboard` evaluator, as a flight
/// computer would.
pub fn step_record(model: &UnitModel, record: &Record) -> Result<Stepped, DtgVibError> {
    step_tables(&tables(model)?, record)
}

/// [`step_record`] of onboard tables of any layout the evaluator reads (a
/// model's, or a file written before), their extra columns named.
pub fn step_tables(t: &Tables, record: &Record) -> Result<Stepped, DtgVibError> {
    let extra: Vec<&[f64]> = t
        .extra
        .iter()
        .map(|n| extra_column(record, n))
        .collect::<Result<_, _>>()?;
    let tables_error = |e: dtg_onboard::Error| ExportError::Tables(e.to_string());
    let m = dtg_onboard::Model::parse(&t.bytes).map_err(tables_error)?;
    let (n_g, n_a) = (m.n_channels(), m.n_accels());
    let mut state = vec![0.0; m.state_len()];
    let mut ev = dtg_onboard::Evaluator::new(m, &mut state).map_err(tables_error)?;
    let mut out = Stepped {
        first_sample: m.window_len() - 1,
        rate_deg_h: vec![Vec::new(); n_g],
        error_deg_h: vec![Vec::new(); n_g],
        accel_g: vec![Vec::new(); n_a],
    };
    let mut push = |o: dtg_onboard::Output| {
        for k in 0..n_g {
            out.rate_deg_h[k].push(o.rate_deg_h[k]);
            out.error_deg_h[k].push(o.error_deg_h[k]);
        }
        for k in 0..n_a {
            out.accel_g[k].push(o.accel_g[k]);
        }
    };
    let (mut x, mut gyro, mut accel) = (vec![0.0; extra.len()], vec![0.0; n_g], vec![0.0; n_a]);
    for i in 0..record.len() {
        for (e, c) in x.iter_mut().zip(&extra) {
            *e = c[i];
        }
        for (k, g) in gyro.iter_mut().enumerate() {
            *g = record.gyro_at(k)[i];
        }
        for (k, a) in accel.iter_mut().enumerate() {
            *a = record.accel_at(k)[i];
        }
        if let Some(o) = ev.step(&gyro, &accel, &x).map_err(tables_error)? {
            push(o);
        }
    }
    for o in ev.flush().into_iter().flatten() {
        push(o);
    }
    Ok(out)
}

/// The record's extra column `name`, or the error naming what it has.
fn extra_column<'r>(record: &'r Record, name: &str) -> Result<&'r [f64], DtgVibError> {
    record.extra(name).ok_or_else(|| {
        DtgVibError::Sysid(sysid::SysidError::WindowSignal {
            name: name.to_string(),
            operating: record.accel_names().to_vec(),
            available: record.extra_names().iter().map(|s| s.to_string()).collect(),
        })
    })
}
